// The streaming quantile sketch against exact quantiles of the same data.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>

#include "report/quantile_sketch.h"

namespace busdecode {
namespace {

// The nearest-rank quantile: the ceil(q * n)-th smallest value.
double exactNearestRank(std::vector<double> v, double q) {
    std::sort(v.begin(), v.end());
    return v[std::size_t(std::max(1.0, std::ceil(q * double(v.size())))) - 1];
}

TEST(QuantileSketch, EmptyHasNoQuantiles) {
    busdecode::QuantileSketch s;
    EXPECT_TRUE(s.empty());
    EXPECT_TRUE(std::isnan(s.median()));
    EXPECT_TRUE(s.histogram(4).empty());
}

TEST(QuantileSketch, QuantilesWithinHalfAPercentOfExact) {
    std::mt19937 rng(42);
    std::lognormal_distribution<double> dist(5.0, 1.2);  // line delays, pauses: skewed
    std::vector<double> values;
    busdecode::QuantileSketch s;
    for (int i = 0; i < 20000; ++i) {
        const double v = dist(rng);
        values.push_back(v);
        s.add(v);
    }
    EXPECT_EQ(s.count(), 20000u);
    EXPECT_DOUBLE_EQ(s.min(), *std::min_element(values.begin(), values.end()));
    EXPECT_DOUBLE_EQ(s.max(), *std::max_element(values.begin(), values.end()));
    for (double q : {0.01, 0.25, 0.5, 0.9, 0.99}) {
        const double exact = exactNearestRank(values, q);
        EXPECT_NEAR(s.quantile(q), exact, exact * 0.0051) << "q=" << q;
    }
    EXPECT_NEAR(s.mean(), std::accumulate(values.begin(), values.end(), 0.0) / 20000, 1e-6);
}

TEST(QuantileSketch, NegativeZeroAndPositiveValuesKeepTheirOrder) {
    busdecode::QuantileSketch s;
    std::vector<double> values;
    for (int i = -50; i <= 50; ++i) {
        s.add(i * 10.0);
        values.push_back(i * 10.0);
    }
    for (double q : {0.1, 0.3, 0.5, 0.7, 0.9}) {
        const double exact = exactNearestRank(values, q);
        EXPECT_NEAR(s.quantile(q), exact, std::fabs(exact) * 0.0051 + 1e-12) << "q=" << q;
    }
    EXPECT_DOUBLE_EQ(s.median(), 0.0);
}

TEST(QuantileSketch, MemoryStaysBoundedOverAHugeRange) {
    busdecode::QuantileSketch s;
    // 1e-12 .. 1e+12 with 1 % buckets would need ~5500 buckets: the smallest get merged.
    for (int e = -120; e <= 120; ++e)
        for (int k = 1; k < 10; ++k)
            s.add(k * std::pow(10.0, e / 10.0));
    EXPECT_EQ(s.count(), 241u * 9u);
    // The high quantiles are still accurate.
    std::vector<double> values;
    for (int e = -120; e <= 120; ++e)
        for (int k = 1; k < 10; ++k)
            values.push_back(k * std::pow(10.0, e / 10.0));
    const double exact = exactNearestRank(values, 0.99);
    EXPECT_NEAR(s.quantile(0.99), exact, exact * 0.0051);
}

TEST(QuantileSketch, HistogramCountsEveryValueOnce) {
    busdecode::QuantileSketch s;
    for (int i = 0; i < 100; ++i)
        s.add(100 + i);  // uniform 100..199
    const auto h = s.histogram(10);
    ASSERT_EQ(h.size(), 10u);
    EXPECT_EQ(std::accumulate(h.begin(), h.end(), std::uint64_t(0)), 100u);
    for (auto n : h)
        EXPECT_NEAR(double(n), 10.0, 3.0);
}

TEST(QuantileSketch, SmallIntegersAreExact) {
    // Each bucket answers with the mean of its values: exact for repeated integers.
    busdecode::QuantileSketch s;
    for (int v : {0, 1, 2, 2, 2, 3, 3, 150, 151})
        s.add(v);
    EXPECT_DOUBLE_EQ(s.median(), 2.0);
    EXPECT_DOUBLE_EQ(s.quantile(0.25), 2.0);
    EXPECT_DOUBLE_EQ(s.quantile(0.75), 3.0);
    EXPECT_DOUBLE_EQ(s.quantile(0.88), 150.0);
}

TEST(QuantileSketch, HighQuantilesOfFewValuesReachTheMaximum) {
    // Four clock rates: the 99th percentile is the fastest, not the third (nearest rank).
    busdecode::QuantileSketch s;
    for (double v : {500146.0, 499819.0, 500660.0, 500091.0})
        s.add(v);
    EXPECT_DOUBLE_EQ(s.quantile(0.99), 500660.0);
    EXPECT_DOUBLE_EQ(s.quantile(0.75), 500146.0);
    EXPECT_DOUBLE_EQ(s.median(), 500091.0);
}

TEST(QuantileSketch, ConstantValueIsExact) {
    busdecode::QuantileSketch s;
    for (int i = 0; i < 1000; ++i)
        s.add(250.0);
    EXPECT_DOUBLE_EQ(s.median(), 250.0);
    EXPECT_DOUBLE_EQ(s.quantile(0.99), 250.0);
}

}  // namespace
}  // namespace busdecode

TEST(QuantileSketch, IntegerFieldsGiveIntegerQuantilesEvenWhenABucketHoldsNeighbours) {
    busdecode::QuantileSketch s;
    for (double v : {151.0, 152.0, 152.0, 152.0})
        s.add(v);  // one 1 % bucket holds both
    EXPECT_EQ(s.median(), 152.0);
    busdecode::QuantileSketch f;
    for (double v : {151.5, 151.5, 151.5, 152.0})
        f.add(v);  // not integers: not rounded
    EXPECT_EQ(f.median(), 151.5);
}
