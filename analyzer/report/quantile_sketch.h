#pragma once
// Streaming quantiles with bounded memory and no second pass: a log-bucketed histogram
// (the DDSketch idea). Every value lands in the bucket [g^(i-1), g^i) of its magnitude,
// so a quantile is known to a relative error of (g-1)/2 whatever the distribution, and
// the number of buckets grows with the logarithm of the value range, not with the count.
// Minimum and maximum are kept exactly, and each bucket answers with the mean of the
// values it holds (exact when they are all equal, as integer fields mostly are).
// Beside the buckets, a LinearHistogram: exact while it has seen few values, and then
// finer than 1 % wherever the values' spread is narrow (clock jitter). Quantiles come
// from whichever of the two is finer at that value; histograms from the linear one.
#include <cstdint>
#include <map>
#include <vector>

#include "linear_histogram.h"

namespace busdecode {

class QuantileSketch {
public:
    // 1 % buckets: quantiles within 0.5 %; at most kMaxBuckets buckets per sign (the
    // smallest magnitudes are merged first when a wider range shows up).
    static constexpr double kGamma = 1.01;
    static constexpr std::size_t kMaxBuckets = 2048;

    void add(double v);
    std::uint64_t count() const { return count_; }
    bool empty() const { return count_ == 0; }
    double min() const { return min_; }
    double max() const { return max_; }
    double mean() const { return count_ ? sum_ / double(count_) : 0.0; }
    // Every value added was a whole number.
    bool allIntegers() const { return all_integers_; }
    // q in [0, 1]; 0 and 1 give the exact min and max. NaN when empty.
    double quantile(double q) const;
    double median() const { return quantile(0.5); }
    // Counts in `bins` equal-width bins between min() and max() (exact for the first
    // LinearHistogram::kBins values, then within one of its bins). Empty when nothing
    // was added.
    std::vector<std::uint64_t> histogram(int bins) const;

private:
    struct Bucket {
        std::uint64_t n = 0;
        double sum = 0;  // of the magnitudes
    };
    int indexOf(double magnitude) const;
    static void cap(std::map<int, Bucket>& buckets);
    template <class F>
    void forEachBucket(F&& f) const;  // ascending value order: f(value, count)

    std::map<int, Bucket> positive_, negative_;  // bucket index -> values
    LinearHistogram linear_;
    std::uint64_t zeros_ = 0;
    std::uint64_t count_ = 0;
    double sum_ = 0, min_ = 0, max_ = 0;
    // Integer fields (cycles, counts) answer with integers: a bucket holding 151 and
    // 152 must not report 151.75 cycles.
    bool all_integers_ = true;
};

}  // namespace busdecode
