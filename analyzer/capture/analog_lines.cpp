#include "analog_lines.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <tuple>

#include <fmt/format.h>

#include "core/options.h"

namespace busdecode {

namespace {

constexpr int kBins = 64;

struct Histogram {
    double lo = 0, hi = 0, width = 0;
    std::array<std::uint32_t, kBins> count{};
    double centre(int b) const { return lo + (b + 0.5) * width; }
};

// The range of the samples, but without the few most outlying at either end when they
// lie far out: one spike must not squeeze both levels into one bin, yet a level of a
// hundred samples stays inside.
std::pair<float, float> robustRange(const std::vector<float>& values) {
    const std::size_t n = values.size();
    const std::size_t trim = std::min(std::max<std::size_t>(n / 4096, 4), n / 64);
    std::vector<float> v = values;
    const auto [mn, mx] = std::minmax_element(v.begin(), v.end());
    const float lowest = *mn, highest = *mx;
    std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(trim), v.end());
    const float lo = v[trim];
    std::nth_element(v.begin(), v.end() - std::ptrdiff_t(trim + 1), v.end());
    const float hi = v[n - 1 - trim];
    const float far = (hi - lo) / 2;
    return {lo - lowest > far ? lo : lowest, highest - hi > far ? hi : highest};
}

Histogram histogramOf(const std::vector<float>& values) {
    Histogram h;
    std::tie(h.lo, h.hi) = robustRange(values);
    h.width = (h.hi - h.lo) / kBins;
    if (!(h.width > 0)) return h;
    // Samples beyond the range count in the end bins.
    for (const float v : values)
        ++h.count[int(std::clamp((v - h.lo) / h.width, 0.0, kBins - 1.0))];
    return h;
}

// The fullest bin in [from, to).
int modeIn(const Histogram& h, int from, int to) {
    int best = from;
    for (int b = from; b < to; ++b)
        if (h.count[b] > h.count[best]) best = b;
    return best;
}

// The two main levels: the fullest bin, and the fullest an eighth of the range or more
// away from it (a third level, such as an open wire's, then does not hide the valley).
std::pair<int, int> twoModes(const Histogram& h) {
    const int first = modeIn(h, 0, kBins);
    const int gap = kBins / 8;
    int second = -1;
    for (int b = 0; b < kBins; ++b)
        if (std::abs(b - first) >= gap && (second < 0 || h.count[b] > h.count[second])) second = b;
    return {std::min(first, second), std::max(first, second)};
}

}  // namespace

LevelEstimate LevelEstimator::estimate() const {
    LevelEstimate e;
    SchmittSettings& s = e.settings;
    s.from_data = true;
    if (values_.empty()) return e;
    const Histogram h = histogramOf(values_);
    const auto [low, high] = h.width > 0 ? twoModes(h) : std::pair<int, int>{0, 0};
    e.levels = h.width > 0 ? std::pair(h.centre(low), h.centre(high)) : std::pair(h.lo, h.lo);
    // Two levels show as two peaks with a valley between them; noise around one level
    // fills the bins between.
    std::uint32_t valley = ~0u;
    for (int b = low + 1; b < high; ++b)
        valley = std::min(valley, h.count[b]);
    const bool two_levels =
        high - low >= kBins / 8 && valley * 5 < h.count[low] && valley * 5 < h.count[high];
    if (!two_levels) {
        s.flat = true;
        s.threshold = (h.lo + h.hi) / 2;
        s.hysteresis = std::max((h.hi - h.lo) * 1.5, 1e-9);
        return e;
    }
    s.threshold = (h.centre(low) + h.centre(high)) / 2;
    s.hysteresis = (h.centre(high) - h.centre(low)) / 10;
    s.levels = e.levels;
    return e;
}

void EdgeOrderer::push(Tick t, std::uint32_t line, std::uint8_t level) {
    const Edge e(t, line, level);
    auto it = held_.end();
    while (it != held_.begin() && (it - 1)->t > t)
        --it;
    held_.insert(it, e);
}

void EdgeOrderer::release(Tick bound, std::vector<Edge>& out) {
    std::size_t n = 0;
    while (n < held_.size() && held_[n].t <= bound)
        out.push_back(held_[n++]);
    held_.erase(held_.begin(), held_.begin() + std::ptrdiff_t(n));
}

std::pair<std::string, double> parseThresholdOption(const std::string& text) {
    const auto eq = text.rfind('=');
    const std::string name = eq == std::string::npos ? "" : text.substr(0, eq);
    const std::string num = eq == std::string::npos ? text : text.substr(eq + 1);
    double v = 0;
    const auto [p, ec] = std::from_chars(num.data(), num.data() + num.size(), v);
    if (num.empty() || ec != std::errc() || p != num.data() + num.size() || !std::isfinite(v) ||
        (eq != std::string::npos && name.empty()))
        throw InputError(fmt::format(
            "--threshold {}: expected VOLTS or SIGNAL=VOLTS (e.g. 1.5 or CLK=1.5)", text));
    return {name, v};
}

double parseHysteresisOption(const std::string& text) {
    double v = 0;
    const auto [p, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
    if (text.empty() || ec != std::errc() || p != text.data() + text.size() || !std::isfinite(v) ||
        v < 0)
        throw InputError(
            fmt::format("--hysteresis {}: expected a number of volts, 0 or more", text));
    return v;
}

}  // namespace busdecode
