#include "signal_quality.h"

#include <algorithm>
#include <cmath>
#include <tuple>

#include <fmt/format.h>

namespace busdecode {

namespace {

// (median, p99) of the durations kept (seconds) in ns; NaN when none.
std::pair<double, double> spread(std::vector<double> d) {
    if (d.empty()) return {NAN, NAN};
    std::sort(d.begin(), d.end());
    const double median = d[d.size() / 2];
    const double p99 = d[std::min(d.size() - 1, d.size() * 99 / 100)];
    return {median * 1e9, p99 * 1e9};
}

std::string spreadText(double median, double p99) {
    if (std::isnan(median)) return "none seen";
    return fmt::format("median {:.4g} ns p99 {:.4g} ns", median, p99);
}

Value nsOrNull(double ns) {
    return std::isnan(ns) ? Value(Null{}) : Value(ns);
}

}  // namespace

SignalFigures SignalQuality::figures() const {
    SignalFigures f;
    f.low_v = low_;
    f.high_v = high_;
    f.swing_v = high_ - low_;
    f.overshoot_pct = f.swing_v > 0 ? 100 * over_ / f.swing_v : 0.0;
    std::tie(f.rise_median_ns, f.rise_p99_ns) = spread(rises_);
    std::tie(f.fall_median_ns, f.fall_p99_ns) = spread(falls_);
    f.rises = rise_count_;
    f.falls = fall_count_;
    return f;
}

std::string SignalQuality::summary(std::uint64_t reversals) const {
    const SignalFigures f = figures();
    return fmt::format(
        "low {:.4g} V, high {:.4g} V, swing {:.4g} V, rise (10-90 %) {}, fall {}, overshoot "
        "{:.0f} % of the swing, {} reversals inside the hysteresis band",
        f.low_v, f.high_v, f.swing_v, spreadText(f.rise_median_ns, f.rise_p99_ns),
        spreadText(f.fall_median_ns, f.fall_p99_ns), f.overshoot_pct, reversals);
}

Event SignalQuality::event(const std::string& line, double threshold, double hysteresis,
                           std::uint64_t reversals) const {
    const SignalFigures f = figures();
    Event e;
    e.proto = "capture";
    e.type = "signal";
    e.add("line", line)
        .add("low_v", f.low_v)
        .add("high_v", f.high_v)
        .add("swing_v", f.swing_v)
        .add("threshold_v", threshold)
        .add("hysteresis_v", hysteresis)
        .add("rise_median_ns", nsOrNull(f.rise_median_ns))
        .add("rise_p99_ns", nsOrNull(f.rise_p99_ns))
        .add("fall_median_ns", nsOrNull(f.fall_median_ns))
        .add("fall_p99_ns", nsOrNull(f.fall_p99_ns))
        .add("rises", f.rises)
        .add("falls", f.falls)
        .add("overshoot_pct", f.overshoot_pct)
        .add("reversals", reversals);
    e.summary = fmt::format("{}: {}", line, summary(reversals));
    return e;
}

}  // namespace busdecode
