// Costs bounded by what is mapped: a VCD declaring more than 2^17 signals keeps only the
// ones a decode can bind (their changes still read right, the others' skipped, an
// undeclared identifier still refused); a CSV header of 10^5 columns is checked in linear
// time. The time and memory figures are benchmark notes (bench/hostile_headers.py), not
// timed tests.
#include <gtest/gtest.h>

#include "capture/capture_reader.h"
#include "robustness_cli.h"

using namespace busdecode;
using namespace busdecode::test;

namespace {

// `n` one-bit signals s0..s<n-1> with identifiers i0..i<n-1> (long ones) but the first
// two, `!` and `"`; changes on s0, s1 and some unmapped ones.
std::string wideVcd(int n, const std::string& extra = "") {
    std::string v =
        "$timescale 1 ns $end\n$scope module top $end\n"
        "$var wire 1 ! s0 $end\n$var wire 1 \" s1 $end\n";
    for (int i = 2; i < n; ++i)
        v += "$var wire 1 i" + std::to_string(i) + " s" + std::to_string(i) + " $end\n";
    v += "$var wire 1 # late $end\n";  // a short identifier declared past the limit
    v += "$upscope $end\n$enddefinitions $end\n#0\n1!\n1\"\n0i7\n";
    v += "#10\n0!\n1i140000\n0#\n#20\n0\"\n1i3\n#30\n1!\n1\"\n" + extra;
    return v;
}

TEST(BoundedCost, WideVcdKeepsOnlyTheSignalsADecodeCanBind) {
    const auto p = caseFile("wide.vcd", wideVcd(140'001));
    OpenOptions o;
    o.read_ahead = false;
    o.wanted_signals = {"s0", "S1", "clk"};
    auto r = openCapture(p, o);
    ASSERT_EQ(r->signals().size(), 2u);  // 140,002 declared
    EXPECT_EQ(r->signals()[0].full_name, "top.s0");
    EXPECT_EQ(r->signals()[1].full_name, "top.s1");
    r->select({{0, -1}, {1, -1}});
    EXPECT_EQ(r->initialLevels(), (std::vector<std::uint8_t>{1, 1}));
    EdgeBlock b;
    std::vector<std::tuple<Tick, unsigned, int>> got;
    while (r->next(b))
        for (const Edge& e : b.edges)
            got.emplace_back(e.t, e.line, e.level);
    const std::vector<std::tuple<Tick, unsigned, int>> want = {
        {10, 0, 0}, {20, 1, 0}, {30, 0, 1}, {30, 1, 1}};
    EXPECT_EQ(got, want);
    ASSERT_EQ(r->notes().size(), 1u);
    EXPECT_EQ(r->notes()[0],
              "140002 signals declared: only the 2 that --map or a role names "
              "were kept");
}

TEST(BoundedCost, NarrowVcdKeepsEverySignal) {
    OpenOptions o;
    o.wanted_signals = {"s0"};
    auto r = openCapture(caseFile("narrow.vcd", wideVcd(100)), o);
    EXPECT_EQ(r->signals().size(), 101u);
    EXPECT_TRUE(r->notes().empty());
}

TEST(BoundedCost, WideVcdStillRefusesAnUndeclaredIdentifier) {
    const auto p = caseFile("wide_bad.vcd", wideVcd(140'001, "#40\n1nosuch\n"));
    const std::string err = oneLineFailure({p, "--proto", "uart", "--map", "rx=s0"});
    EXPECT_NE(err.find("value change for undeclared identifier 'nosuch'"), std::string::npos)
        << err;
}

TEST(BoundedCost, WideVcdDecodesThroughTheCli) {
    const auto p = caseFile("wide_cli.vcd", wideVcd(140'001));
    const RunResult r = runDecode({p, "--proto", "uart", "--map", "rx=s0", "--map", "tx=s1"});
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find("# hint: 140002 signals declared: only the 2 that --map or a role names "
                         "were kept"),
              std::string::npos)
        << r.out.substr(0, 2000);
}

TEST(BoundedCost, CsvHeaderOfManyColumnsFindsItsDuplicate) {
    std::string header = "Time [s]";
    std::string row = "0.0";
    for (int i = 0; i < 100'000; ++i) {
        header += ",c" + std::to_string(i);
        row += ",1";
    }
    const auto ok = caseFile("wide.csv", header + "\n" + row + "\n");
    OpenOptions o;
    EXPECT_EQ(openCapture(ok, o)->signals().size(), 100'000u);
    const auto dup = caseFile("wide_dup.csv", header + ",c99998\n" + row + ",1\n");
    EXPECT_EQ(oneLineFailure({dup, "--proto", "uart", "--map", "rx=c0"}),
              "decode: " + dup + ":1: duplicate column name 'c99998'");
}

}  // namespace
