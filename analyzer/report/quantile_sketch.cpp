#include "quantile_sketch.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace busdecode {

namespace {
// Magnitudes below this count as zero (a femto-anything is noise in a bus capture).
constexpr double kZero = 1e-15;
}  // namespace

int QuantileSketch::indexOf(double m) const {
    return int(std::ceil(std::log(m) / std::log(kGamma)));
}

void QuantileSketch::cap(std::map<int, Bucket>& b) {
    while (b.size() > kMaxBuckets) {
        auto first = b.begin();
        auto second = std::next(first);
        second->second.n += first->second.n;
        second->second.sum += first->second.sum;
        b.erase(first);
    }
}

void QuantileSketch::add(double v) {
    if (!std::isfinite(v)) return;
    if (count_ == 0) {
        min_ = max_ = v;
    } else {
        min_ = std::min(min_, v);
        max_ = std::max(max_, v);
    }
    ++count_;
    sum_ += v;
    linear_.add(v);
    if (v != std::floor(v)) all_integers_ = false;
    if (std::fabs(v) < kZero) {
        ++zeros_;
    } else if (v > 0) {
        auto& b = positive_[indexOf(v)];
        ++b.n;
        b.sum += v;
        cap(positive_);
    } else {
        auto& b = negative_[indexOf(-v)];
        ++b.n;
        b.sum += -v;
        cap(negative_);
    }
}

template <class F>
void QuantileSketch::forEachBucket(F&& f) const {
    for (auto it = negative_.rbegin(); it != negative_.rend(); ++it)
        f(-it->second.sum / double(it->second.n), it->second.n);
    if (zeros_) f(0.0, zeros_);
    for (const auto& [i, b] : positive_)
        f(b.sum / double(b.n), b.n);
}

double QuantileSketch::quantile(double q) const {
    if (count_ == 0) return std::numeric_limits<double>::quiet_NaN();
    if (q <= 0) return min_;
    if (q >= 1) return max_;
    // The nearest rank, ceil(q * n) (1-based): the smallest value with at least q of the
    // values at or below it, so that a p99 of fewer than 100 values is their maximum.
    const auto rank = std::uint64_t(std::max(1.0, std::ceil(q * double(count_)))) - 1;
    std::uint64_t seen = 0;
    double result = max_;
    bool found = false;
    forEachBucket([&](double value, std::uint64_t n) {
        if (found) return;
        seen += n;
        if (seen > rank) {
            result = value;
            found = true;
        }
    });
    // The linear bins' answer when they are finer here than a bucket (or still exact).
    const double resolution = linear_.resolution();
    if (resolution == 0 || resolution < std::fabs(result) * (kGamma - 1))
        result = linear_.valueAtRank(rank);
    if (all_integers_) result = std::round(result);
    return std::clamp(result, min_, max_);
}

std::vector<std::uint64_t> QuantileSketch::histogram(int bins) const {
    return linear_.histogram(bins, min_, max_);
}

}  // namespace busdecode
