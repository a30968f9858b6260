#pragma once
// Equal-width bins that widen to cover whatever they are given, in constant memory: the
// histogram and the fine quantiles of a narrow spread (a 10 MHz clock jittering by
// 0.1 %), which the log-bucketed QuantileSketch lumps into one bucket.
//
// The first kBins values are kept as they are (exact answers for short captures); then
// kBins bins are laid over their range, and a value outside it doubles the bins' width
// (merging neighbours pairwise, extending down or up) until it fits. Each bin keeps the
// count and the sum of its values, and answers with their mean: within one bin width of
// every value in it.
#include <cstdint>
#include <vector>

namespace busdecode {

class LinearHistogram {
public:
    static constexpr int kBins = 256;

    void add(double v);  // finite values only (the caller filters)
    std::uint64_t count() const { return count_; }
    // Counts in `bins` equal-width bins over [lo, hi] (each value, or each bin's mean,
    // clamped into the range). Empty when nothing was added or bins <= 0.
    std::vector<std::uint64_t> histogram(int bins, double lo, double hi) const;
    // The value of 0-based rank `rank` in ascending order: exact while the first values
    // are kept, then the mean of the bin it falls in.
    double valueAtRank(std::uint64_t rank) const;
    // How far valueAtRank() can be from the true value: a bin's width, 0 while exact.
    double resolution() const { return laid_ ? width_ : 0.0; }

private:
    void lay();                 // the first values' range becomes the bins
    void put(double v);         // into its bin, widening first if needed
    void widenDown();           // twice the width, the bins' range extended below
    void widenUp();             // twice the width, extended above
    int binOf(double v) const;  // may be outside [0, kBins)

    std::vector<double> first_;  // the values until kBins of them are seen
    std::vector<std::uint64_t> n_;
    std::vector<double> sum_;
    double lo_ = 0, width_ = 0;
    bool laid_ = false;
    std::uint64_t count_ = 0;
};

}  // namespace busdecode
