// Generated scope captures with known edges, written in every dialect with slow edges,
// noise, ringing and an offset: read back, each edge at its threshold crossing; and
// differential pairs, with and without an open wire.
#include <gtest/gtest.h>

#include <random>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "capture/differential_pairs.h"
#include "capture/scope_csv_writer.h"
#include "capture_util.h"
#include "core/waveform.h"

namespace busdecode::test {
namespace {

// Two lines of random bits of 1 us, 1 ns ticks.
Waveform randomBits(int bits, std::uint64_t seed) {
    WaveBuilder b(Timebase{1, 1'000'000'000}, {"clk", "data"}, {1, 0});
    std::mt19937_64 rng(seed);
    for (int i = 1; i <= bits; ++i) {
        b.setNs(0, 1000.0 * i, i % 2 == 0);
        b.setNs(1, 1000.0 * i + 300, rng() & 1);
    }
    return b.build(b.ticksFromNs(1000.0 * (bits + 3)));
}

AnalogStyle rough(double snr_db) {
    AnalogStyle s;
    s.sample_ns = 10;
    s.low_v = 0.1;
    s.high_v = 5.1;
    s.offset_v = 0.4;
    s.rise_ns = 200;  // 20 % of a bit
    s.snr_db = snr_db;
    s.ringing = 0.15;
    s.ring_ns = 40;
    return s;
}

// Every edge of `truth` read back within `tol_ns`, and no other.
void expectEdges(const Collected& c, const Waveform& truth, double tol_ns) {
    ASSERT_EQ(c.edges.size(), truth.edges.size());
    for (std::size_t i = 0; i < truth.edges.size(); ++i) {
        const Edge& want = truth.edges[i];
        const auto got = std::find_if(c.edges.begin(), c.edges.end(), [&](const Edge& e) {
            return e.line == want.line && e.level == want.level &&
                   std::abs(c.tb.toNsF(double(e.t)) - double(truth.timebase.toNs(want.t))) <=
                       tol_ns;
        });
        if (got == c.edges.end()) {
            double best = 1e9;
            for (const Edge& e : c.edges)
                if (e.line == want.line)
                    best = std::min(best, std::abs(c.tb.toNsF(double(e.t)) -
                                                   double(truth.timebase.toNs(want.t))));
            ADD_FAILURE() << "edge " << i << " at " << want.t << " nearest " << best;
        }
    }
}

TEST(ScopeGenerated, EveryDialectWithNoiseRingingAndOffsetGivesTheEdgesAtTheCrossing) {
    const Waveform w = randomBits(60, 7);
    for (const ScopeDialect d : kScopeDialects) {
        for (const double snr : {20.0, 26.0}) {
            SCOPED_TRACE(fmt::format("{} at {} dB", scopeDialectName(d), snr));
            const std::string p =
                tempCapture(fmt::format("{}_{}.csv", scopeDialectName(d), snr), "");
            AnalogStyle s = rough(snr);
            s.seed = std::uint64_t(snr) * 10 + std::uint64_t(d);
            writeScopeCsv(w, p, d, s);
            const Collected c = collectFile(p, {"clk", "data"});
            // 1 % of a bit: the crossing found between samples of 10 ns through the noise.
            expectEdges(c, w, 10);
        }
    }
}

TEST(ScopeGenerated, DifferentialPairIsTheDifferenceOfItsWires) {
    const Waveform w = randomBits(60, 8);
    AnalogStyle s = rough(23);
    s.differential = true;
    const std::string p = tempCapture("pair.csv", "");
    writeScopeCsv(w, p, ScopeDialect::Keysight, s);
    OpenOptions o;
    o.pairs = {"clk+,clk-", "data+,data-"};
    const Collected c = collectFile(p, {"clk+,clk-", "data+,data-"}, o);
    expectEdges(c, w, 10);
}

TEST(ScopeGenerated, AnOpenWireKeepsDecodingAndIsReportedFromTheMomentItOpened) {
    const Waveform w = randomBits(80, 9);
    AnalogStyle s = rough(23);
    s.differential = true;
    s.open_line = 1;
    s.open_after_ns = 40'150;
    const std::string p = tempCapture("open.csv", "");
    writeScopeCsv(w, p, ScopeDialect::Rigol, s);
    OpenOptions o;
    o.pairs = {"data+,data-"};
    auto r = openCapture(p, o);
    std::vector<LineRef> lines{{findSignal(r->signals(), "data+,data-"), -1}};
    const Collected c = collect(*r, lines);
    Waveform data = w;
    data.edges.erase(std::remove_if(data.edges.begin(), data.edges.end(),
                                    [](const Edge& e) { return e.line != 1; }),
                     data.edges.end());
    for (auto& e : data.edges)
        e = Edge(e.t, 0, std::uint8_t(e.level));
    expectEdges(c, data, 10);
    const auto notes = r->notes();
    const auto fault = std::find_if(notes.begin(), notes.end(), [](const std::string& n) {
        return n.find("pair_fault") != std::string::npos;
    });
    ASSERT_NE(fault, notes.end()) << fmt::format("{}", fmt::join(notes, "\n"));
    EXPECT_NE(fault->find("data- does not follow data+"), std::string::npos) << *fault;
    // From the first bit after the opening on which the open wire should have moved.
    double from = 0;
    ASSERT_EQ(std::sscanf(fault->c_str() + fault->find("from ") + 5, "%lf", &from), 1) << *fault;
    EXPECT_GE(from * 1e9, 40'150 - 1);
    EXPECT_LE(from * 1e9, 40'150 + 2'000);
}

TEST(ScopeGenerated, LogicPairDecodesThePositiveWireAndReportsAStuckOne) {
    WaveBuilder b(Timebase{1, 1'000'000'000}, {"A+", "A-"}, {1, 0});
    for (int i = 1; i <= 40; ++i) {
        b.setNs(0, 1000.0 * i, i % 2 == 0);
        if (i < 20) b.setNs(1, 1000.0 * i + 2, i % 2 != 0);  // from bit 20 on, A- stuck
    }
    const Waveform w = b.build(b.ticksFromNs(45'000));
    auto r = pairedReader(memoryReader(w), {"A+,A-"});
    std::vector<LineRef> lines{{findSignal(r->signals(), "A+,A-"), -1}};
    const Collected c = collect(*r, lines);
    ASSERT_EQ(c.edges.size(), 40u);
    for (std::size_t i = 0; i < c.edges.size(); ++i)
        EXPECT_EQ(c.edges[i].t, Tick(1000 * (i + 1)));
    const auto notes = r->notes();
    ASSERT_EQ(notes.size(), 1u);
    EXPECT_NE(notes[0].find("A+,A-: pair_fault from 0.000020000 s to 0.000045000 s: A- does not "
                            "follow A+"),
              std::string::npos)
        << notes[0];
}

}  // namespace
}  // namespace busdecode::test
