// The Schmitt trigger of analog lines on generated signals with known edges: sub-sample
// timing, noise inside the hysteresis band, levels found from the data, edge order.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "capture/analog_lines.h"
#include "capture/signal_quality.h"
#include "core/options.h"

namespace busdecode {
namespace {

// A square wave with linear edges (rise `rise` ticks) between `lo` and `hi`, plus noise.
struct Square {
    double lo = 0.2, hi = 3.1, period = 1000, rise = 200, sigma = 0;
    double at(double t, std::mt19937& rng) const {
        const double phase = std::fmod(t, period);
        double x;
        if (phase < rise)
            x = phase / rise;
        else if (phase < period / 2)
            x = 1;
        else if (phase < period / 2 + rise)
            x = 1 - (phase - period / 2) / rise;
        else
            x = 0;
        std::normal_distribution<double> noise(0, sigma > 0 ? sigma : 1);
        return lo + x * (hi - lo) + (sigma > 0 ? noise(rng) : 0);
    }
};

TEST(AnalogLines, LevelsFoundFromTheDataGiveMidpointAndATenthOfTheSwing) {
    Square sq;
    sq.sigma = 0.05;
    std::mt19937 rng(1);
    LevelEstimator est;
    for (int t = 0; t < 20000; t += 7)
        est.add(sq.at(t, rng));
    const SchmittSettings s = est.estimate().settings;
    EXPECT_FALSE(s.flat);
    EXPECT_NEAR(s.threshold, 1.65, 0.1);
    EXPECT_NEAR(s.hysteresis, 0.29, 0.03);
}

TEST(AnalogLines, AFlatPrefixGivesABandWiderThanItsNoise) {
    std::mt19937 rng(2);
    std::normal_distribution<double> noise(5, 0.01);
    LevelEstimator est;
    for (int i = 0; i < 5000; ++i)
        est.add(noise(rng));
    const SchmittSettings s = est.estimate().settings;
    EXPECT_TRUE(s.flat);
    SchmittLine line;
    line.configure(s);
    line.start(0, 5);
    double et;
    for (int i = 1; i < 5000; ++i)
        EXPECT_FALSE(line.feed(i, noise(rng), et)) << i;
}

TEST(AnalogLines, EdgesAreTimedAtTheCrossingFinerThanTheSampleGrid) {
    // 37 ticks a sample: the edges (at 100 + k * 500 ticks) fall between samples.
    Square sq;
    sq.sigma = 0.03;
    std::mt19937 rng(3);
    SchmittLine line;
    line.configure({1.65, 0.29, false, false, std::pair{0.2, 3.1}});
    line.start(0, sq.at(0, rng));
    std::vector<double> edges;
    for (double t = 37; t < 20000; t += 37) {
        double et;
        if (line.feed(t, sq.at(t, rng), et)) edges.push_back(et);
    }
    ASSERT_EQ(edges.size(), 40u);
    for (std::size_t i = 0; i < edges.size(); ++i) {
        const double truth = 100 + 500.0 * double(i);  // mid-rise, mid-fall
        // Noise of 0.03 V on a slope of 2.9 V per 200 ticks: a few ticks, not 37.
        EXPECT_NEAR(edges[i], truth, 8) << "edge " << i;
    }
}

TEST(AnalogLines, EdgeOrdererReleasesInTimeOrderUpToTheBound) {
    EdgeOrderer o;
    o.push(50, 0, 1);
    o.push(20, 1, 1);
    o.push(35, 2, 0);
    std::vector<Edge> out;
    o.release(40, out);
    ASSERT_EQ(out.size(), 2u);
    EXPECT_EQ(out[0].t, 20);
    EXPECT_EQ(out[1].t, 35);
    EXPECT_EQ(o.held(), 1u);
    o.release(kMaxEdgeTick, out);
    EXPECT_EQ(out.back().t, 50);
}

TEST(AnalogLines, SignalQualityMeasuresRiseFallAndOvershoot) {
    // Ramps of 100 ns (10-90 %: 80 ns) every 500 ns, sampled each ns, a 15 % overshoot
    // held for 20 ns after each rise.
    Square sq;
    sq.period = 1000;
    sq.rise = 100;
    std::mt19937 rng(4);
    SignalQuality q;
    q.configure(sq.lo, sq.hi);
    for (int t = 0; t < 100'000; ++t) {
        double v = sq.at(t, rng);
        const int phase = t % 1000;
        if (phase >= 100 && phase < 120) v += 0.15 * (sq.hi - sq.lo);
        q.feed(t * 1e-9, v);
    }
    const std::string s = q.summary(3);
    EXPECT_NE(s.find("rise (10-90 %) median 80 ns p99 80 ns"), std::string::npos) << s;
    EXPECT_NE(s.find("fall median 80 ns p99 80 ns"), std::string::npos) << s;
    EXPECT_NE(s.find("overshoot 15 %"), std::string::npos) << s;
    EXPECT_NE(s.find("swing 2.9 V"), std::string::npos) << s;
    EXPECT_NE(s.find("3 reversals"), std::string::npos) << s;
}

TEST(AnalogLines, ThresholdOptionParses) {
    EXPECT_EQ(parseThresholdOption("1.5"), (std::pair<std::string, double>{"", 1.5}));
    EXPECT_EQ(parseThresholdOption("CLK=-0.2"), (std::pair<std::string, double>{"CLK", -0.2}));
    EXPECT_THROW(parseThresholdOption("CLK="), InputError);
    EXPECT_THROW(parseThresholdOption("=1"), InputError);
    EXPECT_THROW(parseThresholdOption("1.5V"), InputError);
}

}  // namespace
}  // namespace busdecode
