#include "linear_histogram.h"

#include <algorithm>
#include <cmath>

namespace busdecode {

namespace {
// Beyond this the bins stop widening (values near the double range's end all share the
// outermost bins rather than overflow the arithmetic).
constexpr double kMaxWidth = 1e300;
}  // namespace

void LinearHistogram::add(double v) {
    ++count_;
    if (laid_) {
        put(v);
        return;
    }
    first_.push_back(v);
    if (first_.size() == std::size_t(kBins)) lay();
}

void LinearHistogram::lay() {
    const auto [mn, mx] = std::minmax_element(first_.begin(), first_.end());
    double span = *mx - *mn;
    // All equal so far: bins a millionth of the value wide, widened as the spread shows.
    if (!(span > 0)) span = *mn != 0 ? std::fabs(*mn) * 1e-6 : 1e-9;
    lo_ = *mn;
    width_ = std::min(span / (kBins - 1), kMaxWidth);  // the largest value in the last bin
    n_.assign(kBins, 0);
    sum_.assign(kBins, 0.0);
    laid_ = true;
    for (double v : first_)
        put(v);
    first_.clear();
    first_.shrink_to_fit();
}

int LinearHistogram::binOf(double v) const {
    const double x = (v - lo_) / width_;
    if (x < 0) return -1;
    if (x >= kBins) return kBins;
    return int(x);
}

void LinearHistogram::put(double v) {
    int b = binOf(v);
    while ((b < 0 || b >= kBins) && width_ < kMaxWidth) {
        if (b < 0)
            widenDown();
        else
            widenUp();
        b = binOf(v);
    }
    b = std::clamp(b, 0, kBins - 1);
    ++n_[std::size_t(b)];
    sum_[std::size_t(b)] += v;
}

void LinearHistogram::widenUp() {
    // Old bin j, [lo + j w, lo + (j + 1) w), lies in new bin j / 2 of width 2w.
    for (int j = 0; j < kBins; ++j) {
        const std::uint64_t n = n_[std::size_t(j)];
        const double s = sum_[std::size_t(j)];
        n_[std::size_t(j)] = 0;
        sum_[std::size_t(j)] = 0;
        n_[std::size_t(j / 2)] += n;
        sum_[std::size_t(j / 2)] += s;
    }
    width_ *= 2;
}

void LinearHistogram::widenDown() {
    // The new range starts kBins old widths lower: old bin j lies in new bin kBins/2 + j/2.
    // Walked from the top, so that a bin is read before it is written.
    for (int j = kBins - 1; j >= 0; --j) {
        const std::uint64_t n = n_[std::size_t(j)];
        const double s = sum_[std::size_t(j)];
        n_[std::size_t(j)] = 0;
        sum_[std::size_t(j)] = 0;
        n_[std::size_t(kBins / 2 + j / 2)] += n;
        sum_[std::size_t(kBins / 2 + j / 2)] += s;
    }
    lo_ -= kBins * width_;
    width_ *= 2;
}

std::vector<std::uint64_t> LinearHistogram::histogram(int bins, double lo, double hi) const {
    if (count_ == 0 || bins <= 0) return {};
    std::vector<std::uint64_t> out(std::size_t(bins), 0);
    const double width = (hi - lo) / bins;
    auto count = [&](double v, std::uint64_t n) {
        v = std::clamp(v, lo, hi);
        const int b = width > 0 ? int((v - lo) / width) : 0;
        out[std::size_t(std::clamp(b, 0, bins - 1))] += n;
    };
    if (!laid_) {
        for (double v : first_)
            count(v, 1);
    } else {
        for (int j = 0; j < kBins; ++j)
            if (n_[std::size_t(j)])
                count(sum_[std::size_t(j)] / double(n_[std::size_t(j)]), n_[std::size_t(j)]);
    }
    return out;
}

double LinearHistogram::valueAtRank(std::uint64_t rank) const {
    if (count_ == 0) return std::nan("");
    if (!laid_) {
        std::vector<double> v = first_;
        const auto k = std::min<std::size_t>(rank, v.size() - 1);
        std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(k), v.end());
        return v[k];
    }
    std::uint64_t seen = 0;
    double last = lo_;
    for (int j = 0; j < kBins; ++j) {
        const std::uint64_t n = n_[std::size_t(j)];
        if (!n) continue;
        last = sum_[std::size_t(j)] / double(n);
        seen += n;
        if (seen > rank) return last;
    }
    return last;
}

}  // namespace busdecode
