#include "report_format.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "capture_stats.h"
#include "core/number_text.h"
#include "sinks/event_format.h"

namespace busdecode {

namespace {
bool endsWith(const std::string& s, std::string_view suffix) {
    return s.size() >= suffix.size() &&
           s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}
}  // namespace

std::string formatFrequency(double hz) {
    // Pick the unit after rounding, so 999999.9999 Hz reads 1.000 MHz, not 1000.000 kHz;
    // GHz at most (bus clocks).
    const int p = std::min(siPower(std::fabs(hz) * (1 + 1e-7)), 3);
    if (p == 0) return fmt::format("{:.3g} Hz", hz);
    return fmt::format("{:.3f} {}Hz", hz / siScale(p), siPrefix(p));
}

std::string formatFieldValue(const std::string& key, double v) {
    if (!std::isfinite(v)) return "-";
    if (endsWith(key, "_ns")) return formatDuration(v);
    if (endsWith(key, "_us")) return formatDuration(v * 1e3);
    if (endsWith(key, "_hz")) return formatFrequency(v);
    // Positions and counts exactly: 1193046 is not 1.19305e+06.
    if (v == std::trunc(v) && std::abs(v) < 9007199254740992.0) return fmt::format("{:.0f}", v);
    return fmt::format("{:.6g}", v);
}

std::string formatBytes(std::uint64_t b) {
    if (b >= 1'000'000'000) return fmt::format("{:.1f} GB", double(b) / 1e9);
    if (b >= 1'000'000) return fmt::format("{:.1f} MB", double(b) / 1e6);
    if (b >= 1'000) return fmt::format("{:.1f} kB", double(b) / 1e3);
    return fmt::format("{} B", b);
}

std::string formatTime(double ns) {
    return formatDuration(ns);
}

std::vector<std::string> textHistogram(const std::string& key, const QuantileSketch& s, int bins,
                                       int width) {
    std::vector<std::string> rows;
    if (s.empty()) return rows;
    if (s.min() == s.max()) bins = 1;
    // Whole numbers over a short range (cycles, repeats): one row per value, no 0 .. 0.625.
    const bool per_value = s.allIntegers() && s.max() - s.min() < bins;
    if (per_value) bins = int(s.max() - s.min()) + 1;
    const auto counts = s.histogram(bins);
    const std::uint64_t peak = *std::max_element(counts.begin(), counts.end());
    const double step = per_value ? 1.0 : (s.max() - s.min()) / bins;
    for (int i = 0; i < bins; ++i) {
        const double lo = s.min() + step * i;
        const double hi = i + 1 == bins ? s.max() : lo + step;
        const int bar = peak ? int(std::lround(double(counts[i]) * width / double(peak))) : 0;
        // A non-empty bin always shows at least one mark.
        const int marks = counts[i] && bar == 0 ? 1 : bar;
        const std::string range =
            per_value ? fmt::format("{:>12}    {:<12}", formatFieldValue(key, lo), "")
                      : fmt::format("{:>12} .. {:<12}", formatFieldValue(key, lo),
                                    formatFieldValue(key, hi));
        rows.push_back(
            fmt::format("{} |{:<{}}| {}", range, std::string(marks, '#'), width, counts[i]));
    }
    return rows;
}

}  // namespace busdecode
