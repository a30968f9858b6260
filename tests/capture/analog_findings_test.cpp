// Scope captures whose edges are easy to lose: a given threshold and hysteresis whose fit
// window would reach a level, one out-of-range sample among the levels, a line idle for
// longer than the prefix its levels are found in, and PicoScope columns in millivolts.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include <fmt/format.h>

#include "capture/analog_lines.h"
#include "capture/scope_csv_writer.h"
#include "capture_util.h"
#include "core/waveform.h"

namespace busdecode::test {
namespace {

constexpr double kSampleNs = 20;
constexpr int kBitSamples = 50;  // bits of 1 us
// Bits of one line: idle high, then a few 8N1 characters.
const std::vector<int> kBits = [] {
    std::vector<int> bits(10, 1);
    for (const int c : {0x48, 0x55, 0xAA, 0x00, 0xFF}) {
        bits.push_back(0);
        for (int i = 0; i < 8; ++i)
            bits.push_back((c >> i) & 1);
        bits.push_back(1);
    }
    bits.insert(bits.end(), 10, 1);
    return bits;
}();

// The level of sample k (0 or 1).
int levelAt(std::size_t k) {
    return kBits[k / kBitSamples];
}
std::size_t sampleCount() {
    return kBits.size() * kBitSamples;
}

// The truth's edge times in ns, after `idle` samples.
std::vector<double> truthNs(std::size_t idle) {
    std::vector<double> out;
    for (std::size_t i = 1; i < kBits.size(); ++i)
        if (kBits[i] != kBits[i - 1]) out.push_back(double(idle + i * kBitSamples) * kSampleNs);
    return out;
}

// Every edge of the truth within one sample, and no other.
void expectTruth(const Collected& c, std::size_t idle = 0) {
    const std::vector<double> want = truthNs(idle);
    ASSERT_EQ(c.edges.size(), want.size());
    for (std::size_t i = 0; i < want.size(); ++i)
        EXPECT_NEAR(c.tb.toNsF(double(c.edges[i].t)), want[i], kSampleNs) << "edge " << i;
}

// The wave as Rigol writes it: `idle` samples at `idle_v` first, then the bits between
// 0 V and `high_v`; `spike` at sample 200 (high).
struct Wave {
    std::size_t idle = 0;
    double idle_v = 3.3, high_v = 3.3, noise = 0;
    std::string spike;
};
std::string rigolText(const Wave& w = {}) {
    std::string s = "X,CH1,Start,Increment,\nSequence,Volt,0.000000e+00,2.000000e-08\n";
    std::mt19937 rng(9);
    std::normal_distribution<double> noise(0, w.noise > 0 ? w.noise : 1);
    for (std::size_t k = 0; k < w.idle + sampleCount(); ++k) {
        const double v = k < w.idle ? w.idle_v : levelAt(k - w.idle) ? w.high_v : 0;
        if (k == 200 && !w.spike.empty())
            s += fmt::format("{},{},\n", k, w.spike);
        else
            s += fmt::format("{},{:.3f},\n", k, v + (w.noise > 0 ? noise(rng) : 0));
    }
    return s;
}

OpenOptions given(double threshold, double hysteresis = -1) {
    OpenOptions o;
    o.thresholds = {{"", threshold}};
    o.hysteresis = hysteresis;
    return o;
}

TEST(AnalogFindings, AGivenThresholdAndHysteresisThatFitTheSignalKeepEveryEdge) {
    const std::string p = tempCapture("step.csv", rigolText());
    // A window of 2.5 bands around 1.65 V reached both levels: every edge stayed pending.
    expectTruth(collectFile(p, {"CH1"}, given(1.65, 1.0)));
    // With the swing's hysteresis, a window around 0.8 V reached the low level.
    expectTruth(collectFile(p, {"CH1"}, given(0.8)));
    expectTruth(collectFile(p, {"CH1"}));
}

TEST(AnalogFindings, OneOutOfRangeSampleLeavesTheLevelsAlone) {
    for (const std::string spike : {"40.000", "200", "9.9E+37"}) {
        SCOPED_TRACE(spike);
        const std::string p = tempCapture(
            "spike.csv",
            rigolText({.idle = 0, .idle_v = 3.3, .high_v = 3.3, .noise = 0, .spike = spike}));
        expectTruth(collectFile(p, {"CH1"}));
    }
    // Keysight's over-range value, in its own layout.
    std::string k = "x-axis,1\nsecond,Volt\n";
    for (std::size_t i = 0; i < sampleCount(); ++i)
        k += fmt::format("{:.8E},{}\n", double(i) * kSampleNs * 1e-9,
                         i == 300     ? "9.9E+37"
                         : levelAt(i) ? "3.30000E+00"
                                      : "0.00000E+00");
    expectTruth(collectFile(tempCapture("keysight.csv", k), {"CH1"}));
}

TEST(AnalogFindings, ALevelOfAFewHundredSamplesIsStillFound) {
    std::mt19937 rng(4);
    std::normal_distribution<double> noise(0, 0.02);
    LevelEstimator est;
    for (int i = 0; i < (1 << 18) - 301; ++i)
        est.add(noise(rng));
    for (int i = 0; i < 300; ++i)
        est.add(3.3 + noise(rng));
    est.add(40);
    const LevelEstimate found = est.estimate();
    EXPECT_FALSE(found.settings.flat);
    EXPECT_NEAR(found.settings.threshold, 1.65, 0.1);
    const auto [low, high] = found.levels;
    EXPECT_NEAR(low, 0, 0.1);
    EXPECT_NEAR(high, 3.3, 0.1);
}

TEST(AnalogFindings, PicoScopeMillivoltsAreVolts) {
    std::string s = "Time,Channel A,Channel B\n(us),(mV),(V)\n\n";
    for (std::size_t k = 0; k < sampleCount(); ++k)
        s += fmt::format("{:.5f},{},{}\n", double(k) * kSampleNs / 1000,
                         levelAt(k) ? "3300.00" : "0.00", levelAt(k) ? "3.30000" : "0.00000");
    const std::string p = tempCapture("pico_mv.csv", s);
    // --threshold is in volts, whatever the column's unit.
    expectTruth(collectFile(p, {"A"}, given(1.6)));
    expectTruth(collectFile(p, {"B"}, given(1.6)));
    auto r = openCapture(p, {});
    collect(*r, {LineRef{0, -1}});
    const auto notes = r->notes();
    ASSERT_FALSE(notes.empty());
    EXPECT_NE(notes[0].find("threshold 1.65 V"), std::string::npos) << notes[0];
}

TEST(AnalogFindings, PicoScopeOverRangeAndALatin1MicroSecond) {
    // "(\xb5s)": µ in Latin-1; "∞": a sample beyond the range, on every 50th high one.
    std::string s = "Time,Channel A\n(\xb5s),(V)\n\n";
    for (std::size_t k = 0; k < sampleCount(); ++k)
        s += fmt::format("{:.5f},{}\n", double(k) * kSampleNs / 1000,
                         !levelAt(k)   ? "0.00"
                         : k % 50 == 0 ? "\xe2\x88\x9e"
                                       : "3.30");
    expectTruth(collectFile(tempCapture("pico_inf.csv", s), {"A"}));
}

// Longer than the prefix the levels are found in (2^18 samples).
constexpr std::size_t kIdle = 300'000;

TEST(AnalogFindings, AnIdleStartLongerThanThePrefixKeepsEveryEdge) {
    for (const double high : {3.3, 3.0}) {
        SCOPED_TRACE(high);
        const std::string p = tempCapture(
            "idle.csv",
            rigolText({.idle = kIdle, .idle_v = 3.3, .high_v = high, .noise = 0.02, .spike = ""}));
        auto r = openCapture(p, {});
        const Collected c = collect(*r, {LineRef{0, -1}});
        ASSERT_EQ(c.initial, std::vector<std::uint8_t>{1});
        expectTruth(c, kIdle);
        const auto notes = r->notes();
        ASSERT_EQ(notes.size(), 1u);
        EXPECT_NE(notes[0].find("after its idle start"), std::string::npos) << notes[0];
        const auto at = notes[0].find("threshold ");
        ASSERT_NE(at, std::string::npos) << notes[0];
        EXPECT_NEAR(std::stod(notes[0].substr(at + 10)), high / 2, 0.1) << notes[0];
    }
}

// CH2's edges while CH1's samples are held outnumber what an edge block holds: CH1 is
// judged early rather than stall the reader.
TEST(AnalogFindings, AnotherLinesEdgesWaitForAnIdleLineAndStayInOrder) {
    std::string s = "X,CH1,CH2,Start,Increment,\nSequence,Volt,Volt,0.000000e+00,2.000000e-08\n";
    std::mt19937 rng(5);
    std::normal_distribution<double> noise(0, 0.02);
    // CH1 idles on after its characters, so it is held for more than kEdgeBlockSize
    // edges of CH2.
    const std::size_t n = kIdle + sampleCount() + 70'000;
    for (std::size_t k = 0; k < n; ++k) {
        const bool idle = k < kIdle || k >= kIdle + sampleCount();
        const double v1 = idle || levelAt(k - kIdle) ? 3.3 : 0;
        s += fmt::format("{},{:.3f},{:.3f},\n", k, v1 + noise(rng), (k / 3) % 2 ? 3.3 : 0.0);
    }
    auto r = openCapture(tempCapture("two.csv", s), {});
    const Collected c = collect(*r, {LineRef{0, -1}, LineRef{1, -1}});
    Collected one = c;
    one.edges.clear();
    std::size_t second = 0;
    for (std::size_t i = 0; i < c.edges.size(); ++i) {
        if (i > 0) {
            ASSERT_LE(c.edges[i - 1].t, c.edges[i].t) << i;
        }
        if (c.edges[i].line == 0) one.edges.push_back(c.edges[i]);
        second += c.edges[i].line == 1;
    }
    expectTruth(one, kIdle);
    EXPECT_EQ(second, (n - 1) / 3);
}

TEST(AnalogFindings, ALineIdleAllThroughHasNoEdgesAndSaysItsThresholdIsAGuess) {
    std::string s = "X,CH1,Start,Increment,\nSequence,Volt,0.000000e+00,2.000000e-08\n";
    std::mt19937 rng(3);
    std::normal_distribution<double> noise(3.3, 0.02);
    for (std::size_t k = 0; k < kIdle; ++k)
        s += fmt::format("{},{:.3f},\n", k, noise(rng));
    auto r = openCapture(tempCapture("flat.csv", s), {});
    const Collected c = collect(*r, {LineRef{0, -1}});
    EXPECT_TRUE(c.edges.empty());
    const auto notes = r->notes();
    ASSERT_EQ(notes.size(), 2u);
    EXPECT_NE(notes[0].find("a guess"), std::string::npos) << notes[0];
}

}  // namespace
}  // namespace busdecode::test
