// The widening equal-width bins behind report histograms, against exact counts.
#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <random>

#include "report/linear_histogram.h"
#include "report/quantile_sketch.h"

namespace busdecode {
namespace {

std::uint64_t total(const std::vector<std::uint64_t>& h) {
    return std::accumulate(h.begin(), h.end(), std::uint64_t(0));
}

TEST(LinearHistogram, FewValuesAreCountedExactly) {
    // Four clock readings spread over 0.17 %: one 1 % log bucket would hold them all.
    LinearHistogram h;
    for (double v : {499819.0, 500146.0, 500146.0, 500660.0})
        h.add(v);
    EXPECT_EQ(h.resolution(), 0.0);
    EXPECT_EQ(h.histogram(8, 499819.0, 500660.0),
              (std::vector<std::uint64_t>{1, 0, 0, 2, 0, 0, 0, 1}));
    EXPECT_EQ(h.valueAtRank(0), 499819.0);
    EXPECT_EQ(h.valueAtRank(1), 500146.0);
    EXPECT_EQ(h.valueAtRank(3), 500660.0);
}

TEST(LinearHistogram, NarrowSpreadKeepsItsShapeOverManyValues) {
    // A 10 MHz clock jittering uniformly by +-0.1 %, then a slower stretch: two blocks.
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> fast(9.99e6, 10.01e6), slow(9.95e6, 9.96e6);
    LinearHistogram h;
    std::vector<double> all;
    for (int i = 0; i < 40000; ++i) {
        const double v = i < 30000 ? fast(rng) : slow(rng);
        h.add(v);
        all.push_back(v);
    }
    const double lo = *std::min_element(all.begin(), all.end());
    const double hi = *std::max_element(all.begin(), all.end());
    const auto counts = h.histogram(6, lo, hi);  // 10 kHz per bin
    ASSERT_EQ(counts.size(), 6u);
    EXPECT_EQ(total(counts), 40000u);
    // Exact counts per display bin, for comparison: the bins' means land within one
    // linear bin (60 kHz / 256 at most twice widened) of their values.
    std::vector<std::uint64_t> exact(6, 0);
    for (double v : all)
        ++exact[std::size_t(std::clamp(int((v - lo) / ((hi - lo) / 6)), 0, 5))];
    for (std::size_t i = 0; i < 6; ++i)
        EXPECT_NEAR(double(counts[i]), double(exact[i]), 0.02 * 40000) << "bin " << i;
    EXPECT_GT(counts[0], 9000u);  // the slow stretch
    EXPECT_EQ(counts[2], 0u);     // nothing between the two
    // Quantiles to within one bin width, far finer than a 1 % bucket (100 kHz).
    std::sort(all.begin(), all.end());
    EXPECT_GT(h.resolution(), 0.0);
    EXPECT_LT(h.resolution(), 1000.0);
    for (double q : {0.1, 0.5, 0.9}) {
        const auto rank = std::uint64_t(q * double(all.size() - 1));
        EXPECT_NEAR(h.valueAtRank(rank), all[rank], h.resolution()) << "q=" << q;
    }
}

TEST(LinearHistogram, WidensDownAndUpKeepingEveryCount) {
    LinearHistogram h;
    for (int i = 0; i < LinearHistogram::kBins; ++i)
        h.add(1000 + i);  // laid over 1000..1255
    h.add(-5000);         // far below: widened downwards
    h.add(1e6);           // far above: widened upwards
    EXPECT_EQ(h.count(), std::uint64_t(LinearHistogram::kBins + 2));
    const auto counts = h.histogram(4, -5000, 1e6);
    EXPECT_EQ(total(counts), h.count());
    EXPECT_EQ(counts[0], std::uint64_t(LinearHistogram::kBins + 1));  // -5000 and 1000..1255
    EXPECT_EQ(counts[3], 1u);
    EXPECT_NEAR(h.valueAtRank(0), -5000, h.resolution());
    EXPECT_NEAR(h.valueAtRank(h.count() - 1), 1e6, h.resolution());
}

TEST(LinearHistogram, HugeValuesStopWideningInsteadOfOverflowing) {
    LinearHistogram h;
    for (int i = 0; i < LinearHistogram::kBins; ++i)
        h.add(i);
    h.add(1.7e308);
    h.add(-1.7e308);
    EXPECT_EQ(total(h.histogram(3, -1.7e308, 1.7e308)), h.count());
}

TEST(QuantileSketch, HistogramOfANarrowSpreadPutsTheExtremesInTheEndBins) {
    // The SSI report case: min and max of four clock readings fell in the middle bin.
    QuantileSketch s;
    for (double v : {499819.0, 500146.0, 500146.0, 500660.0})
        s.add(v);
    const auto h = s.histogram(8);
    ASSERT_EQ(h.size(), 8u);
    EXPECT_EQ(h.front(), 1u);
    EXPECT_EQ(h.back(), 1u);
    EXPECT_EQ(s.median(), 500146.0);  // exact, not a bucket's mean
}

}  // namespace
}  // namespace busdecode
