// The VCD reader's state letters: IEEE 1364/1800 `0 1 x z` and VHDL's (GHDL, NVC)
// `U X 0 1 Z W L H -` in either case, on scalars and vector bits. L/H are levels; the
// others keep the line's level. --rate given for a VCD sets one sample per time unit,
// and a Vivado ILA file (sample indices as 1 ps times) gets a hint to give it.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include "capture/capture_reader.h"
#include "robustness_cli.h"

using namespace busdecode;
using namespace busdecode::test;

namespace {

struct Read {
    std::vector<Edge> edges;
    std::vector<std::uint8_t> initial;
    Timebase tb;
};

Read readAll(const std::string& path, const std::vector<LineRef>& lines, OpenOptions o = {}) {
    o.read_ahead = false;  // the sequential reader (the pieces are the same tokeniser)
    auto r = openCapture(path, o);
    r->select(lines);
    Read out;
    out.initial = r->initialLevels();
    out.tb = r->timebase();
    EdgeBlock b;
    while (r->next(b))
        out.edges.insert(out.edges.end(), b.edges.begin(), b.edges.end());
    return out;
}

TEST(VcdStates, NineValueStatesOnScalars) {
    const auto p = caseFile("ghdl.vcd",
                            "$timescale 1 ns $end\n$var wire 1 ! a $end\n$var wire 1 \" b $end\n"
                            "$enddefinitions $end\n#0\nU!\nu\"\n#5\nL!\n#10\nH!\nW\"\n"
                            "#15\n-!\nl\"\n#20\nh!\nZ\"\n#25\nX!\nh\"\n#30\nw!\n0!\n");
    const Read r = readAll(p, {{0, -1}, {1, -1}});
    EXPECT_EQ(r.initial, (std::vector<std::uint8_t>{1, 1}));  // unknown at first: idle high
    const std::vector<Edge> want = {{5, 0, 0}, {10, 0, 1}, {15, 1, 0}, {25, 1, 1}, {30, 0, 0}};
    ASSERT_EQ(r.edges.size(), want.size());
    for (std::size_t i = 0; i < want.size(); ++i) {
        EXPECT_EQ(r.edges[i].t, want[i].t) << i;
        EXPECT_EQ(r.edges[i].line, want[i].line) << i;
        EXPECT_EQ(r.edges[i].level, want[i].level) << i;
    }
}

TEST(VcdStates, NineValueStatesInVectors) {
    const auto p = caseFile("ghdl_vec.vcd",
                            "$timescale 1 ns $end\n$var wire 4 ! v [3:0] $end\n"
                            "$enddefinitions $end\n#0\nbUUUU !\n#5\nbLHLH !\n#10\nbW-HL !\n"
                            "#15\nbh !\n#20\nbUZ10 !\n");
    const Read r = readAll(p, {{0, 0}, {0, 1}, {0, 2}, {0, 3}});
    // Bits from the right. bit 0: U H L h 0; bit 1: U L H 0 (extended) 1; bit 2: U H - 0 Z;
    // bit 3: U L W 0 U. Unknowns keep the level (1 before any known one).
    std::vector<std::tuple<Tick, unsigned, int>> got;
    for (const Edge& e : r.edges)
        got.emplace_back(e.t, e.line, e.level);
    const std::vector<std::tuple<Tick, unsigned, int>> want = {{5, 1, 0},  {5, 3, 0},  {10, 0, 0},
                                                               {10, 1, 1}, {15, 0, 1}, {15, 1, 0},
                                                               {15, 2, 0}, {20, 0, 0}, {20, 1, 1}};
    EXPECT_EQ(got, want);
}

TEST(VcdStates, GhdlStatesOnUnmappedScalarsThroughTheCli) {
    const auto p =
        caseFile("ghdl_cli.vcd",
                 "$timescale 1 ns $end\n$var wire 1 ! cs $end\n$var wire 1 \" sclk $end\n"
                 "$var wire 1 # mosi $end\n$var wire 1 $ spare $end\n"
                 "$enddefinitions $end\n#0\n1!\n1\"\n0#\nU$\n#10\n0!\n-$\n#20\nW$\n1!\n");
    const RunResult r = runDecode({p, "--proto", "spi"});
    EXPECT_EQ(r.status, 0) << r.err;
}

TEST(VcdStates, RateOverridesTheTimescale) {
    const auto p = caseFile("rate.vcd",
                            "$timescale 1ps $end\n$var wire 1 ! a $end\n"
                            "$enddefinitions $end\n#0\n1!\n#1\n0!\n#3\n1!\n");
    OpenOptions o;
    o.rate_hz = 2.5e6;
    const Read r = readAll(p, {{0, -1}}, o);
    EXPECT_EQ(r.tb.toNs(1), 400);  // one sample per time unit at 2.5 MS/s
    EXPECT_EQ(r.tb.toNs(3), 1200);
    EXPECT_EQ(readAll(p, {{0, -1}}).tb.toNs(1000), 1);  // without --rate: 1 ps
}

TEST(VcdStates, VivadoIlaSampleIndicesGetAHint) {
    const std::string vcd =
        "$version\n Vivado v2020.1 (64-bit)\n$end\n$timescale\n 1ps\n$end\n"
        "$scope module dut $end\n$var reg 1 ! rx $end\n$upscope $end\n"
        "$enddefinitions $end\n#0\n$dumpvars\n1!\n$end\n#1\n0!\n#2\n1!\n";
    const auto p = caseFile("ila.vcd", vcd);
    const RunResult r = runDecode({p, "--proto", "uart", "--map", "rx=rx", "--format", "jsonl"});
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.err.find("hint: times look like Vivado ILA sample indices under $timescale 1ps: "
                         "give the sample clock with --rate HZ"),
              std::string::npos)
        << r.err;
    const RunResult with_rate =
        runDecode({p, "--proto", "uart", "--map", "rx=rx", "--format", "jsonl", "--rate", "1e6"});
    EXPECT_EQ(with_rate.status, 0);
    EXPECT_EQ(with_rate.err.find("Vivado"), std::string::npos) << with_rate.err;
    // A simulation's VCD at 1 ps steps of nanoseconds is no ILA.
    std::string sim = vcd;
    sim.replace(sim.find("#1\n"), 3, "#5000\n");
    sim.replace(sim.find("#2\n"), 3, "#9000\n");
    const auto q = caseFile("sim.vcd", sim);
    const RunResult s = runDecode({q, "--proto", "uart", "--map", "rx=rx", "--format", "jsonl"});
    EXPECT_EQ(s.err.find("Vivado"), std::string::npos) << s.err;
}

}  // namespace

// Unknown states on mapped lines keep the level and are counted in the summary's notes,
// the same whether the file is read sequentially or in pieces on two threads.
TEST(VcdStates, UnknownStatesOnMappedLinesAreCounted) {
    std::string text =
        "$timescale 1 ns $end\n$var wire 1 ! a $end\n$var wire 4 \" v [3:0] $end\n"
        "$var wire 1 # spare $end\n$enddefinitions $end\n#0\n0!\nb0000 \"\n";
    // Per step: a scalar x, a vector with two unknown bits of the two mapped, an
    // unmapped x (not counted), then known levels again.
    for (int t = 1; t <= 200; ++t)
        text += fmt::format("#{}\nx!\nbz1u0 \"\nx#\n#{}\n1!\nb0000 \"\n", 10 * t, 10 * t + 5);
    const auto p = caseFile("unknowns.vcd", text);
    const std::string want = "400 value changes of mapped lines to x, z, u, w or -";
    for (const bool pieces : {false, true}) {
        OpenOptions o;
        o.read_ahead = pieces;
        o.vcd_piece_bytes = 61;
        o.vcd_boundary_search = 64;
        auto r = openCapture(p, o);
        r->select({{0, -1}, {1, 1}});  // a, and v's bit 1 (x then 0: unknown once per step)
        r->initialLevels();
        EdgeBlock b;
        std::size_t edges = 0;
        while (r->next(b))
            edges += b.edges.size();
        EXPECT_EQ(edges, 1u) << pieces;  // a: 0, kept through x, then 1 for good
        std::string notes;
        for (const auto& n : r->notes())
            notes += n + "\n";
        EXPECT_NE(notes.find(want), std::string::npos) << pieces << ": " << notes;
    }
}
