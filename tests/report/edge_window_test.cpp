// The report's bounded windows of recent edges and voltage samples: what an event to be
// drawn gets of them (edges in its window, the voltage trace thinned to the lowest and
// highest sample per column, the trigger), and what is said when the rings no longer
// reach back far enough.
#include <gtest/gtest.h>

#include <cmath>

#include "report/edge_window.h"
#include "report/waveform_svg.h"
#include "test_events.h"

namespace busdecode {
namespace {

CaptureFacts twoLines() {
    CaptureFacts f = test::facts(1'000'000);
    f.bindings = {{"bissc", "bissc", "ma", "MA", 0}, {"bissc", "bissc", "sl", "SLO", 1}};
    return f;
}

// A 1 MHz square wave on line 0 between 0 V and 5 V, sampled every ns from `from` to `to`,
// with one spike of 7 V at t = 5003.
void feedSquare(EdgeWindows& w, Tick from, Tick to) {
    std::vector<VoltSample> volts;
    std::vector<Edge> edges;
    for (Tick t = from; t < to; ++t) {
        const bool high = (t / 500) % 2;
        volts.push_back({t, t == 5003 ? 7.0f : high ? 5.0f : 0.0f, 0});
        if (t % 500 == 0) edges.push_back({t, 0, std::uint8_t(high)});
        if (volts.size() == 4096 || t + 1 == to) {
            w.addVolts(volts, {{0, 2.5f, 0.5f}});
            volts.clear();
        }
    }
    w.addEdges(edges.data(), edges.data() + edges.size());
}

TEST(EdgeWindow, AnalogLineKeepsItsVoltageAndTrigger) {
    EdgeWindows w;
    w.begin(twoLines());
    feedSquare(w, 0, 20000);
    Event e = test::bisscFrame(4000, 1);
    e.end = 8000;
    e.error("crc");
    w.offer(e);
    ASSERT_EQ(w.waves().size(), 1u);
    const FrameWave& f = w.waves()[0];
    ASSERT_EQ(f.lines.size(), 2u);
    const LineWave& ma = f.lines[0];
    EXPECT_TRUE(ma.analog);
    EXPECT_TRUE(ma.trace_complete);
    EXPECT_FLOAT_EQ(ma.threshold, 2.5f);
    EXPECT_FLOAT_EQ(ma.hysteresis, 0.5f);
    // 4000 + 2 x 500 ns margin of samples thinned to at most two per column.
    EXPECT_LE(ma.trace.size(), 2 * EdgeWindows::kTraceColumns);
    EXPECT_GT(ma.trace.size(), EdgeWindows::kTraceColumns / 2);
    float lo = 99, hi = -99;
    for (std::size_t i = 0; i < ma.trace.size(); ++i) {
        const auto& [t, v] = ma.trace[i];
        EXPECT_GE(t, f.from);
        EXPECT_LE(t, f.to);
        if (i) {
            EXPECT_GT(t, ma.trace[i - 1].first);  // time order kept
        }
        lo = std::min(lo, v);
        hi = std::max(hi, v);
    }
    EXPECT_EQ(lo, 0.0f);
    EXPECT_EQ(hi, 7.0f);              // a one-sample spike survives the thinning
    EXPECT_EQ(ma.edges.size(), 11u);  // every 500 ns from 3500 to 8500
    // The digital line beside it has no trace.
    EXPECT_FALSE(f.lines[1].analog);
    EXPECT_TRUE(f.lines[1].trace.empty());

    const std::string svg = waveformSvg(f, Timebase{1, 1'000'000'000}, {});
    EXPECT_NE(svg.find(R"(<path class="volt-trace" data-role="ma")"), std::string::npos);
    EXPECT_NE(svg.find(R"(<line class="threshold" data-role="ma")"), std::string::npos);
    EXPECT_NE(svg.find(R"(<rect class="hysteresis" data-role="ma")"), std::string::npos);
    EXPECT_NE(svg.find("threshold 2.5 V, hysteresis 0.5 V"), std::string::npos);
    EXPECT_EQ(svg.find(R"(class="volt-trace" data-role="sl")"), std::string::npos);
}

TEST(EdgeWindow, TraceSaysWhenItsRingNoLongerReachesTheEvent) {
    EdgeWindows w;
    w.begin(twoLines());
    const Tick n = Tick(EdgeWindows::kRingVolts);
    feedSquare(w, 0, 2 * n);
    Event e = test::bisscFrame(n / 2, 1);  // long gone from the ring
    e.end = n + 1000;
    w.offer(e);
    ASSERT_EQ(w.waves().size(), 1u);
    const LineWave& ma = w.waves()[0].lines[0];
    EXPECT_TRUE(ma.analog);
    EXPECT_FALSE(ma.trace_complete);
    EXPECT_FALSE(ma.trace.empty());
    EXPECT_GE(ma.trace.front().first, n);  // what the ring still held
    const std::string svg = waveformSvg(w.waves()[0], Timebase{1, 1'000'000'000}, {});
    EXPECT_NE(svg.find("(earlier samples not kept)"), std::string::npos);
}

}  // namespace
}  // namespace busdecode
