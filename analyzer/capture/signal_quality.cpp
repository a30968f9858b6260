#include "signal_quality.h"

#include <algorithm>

#include <fmt/format.h>

namespace busdecode {

namespace {

// "median 41 ns p99 55 ns" of the durations kept (seconds).
std::string spread(std::vector<double> d) {
    if (d.empty()) return "none seen";
    std::sort(d.begin(), d.end());
    const double median = d[d.size() / 2];
    const double p99 = d[std::min(d.size() - 1, d.size() * 99 / 100)];
    return fmt::format("median {:.4g} ns p99 {:.4g} ns", median * 1e9, p99 * 1e9);
}

}  // namespace

std::string SignalQuality::summary(std::uint64_t reversals) const {
    const double swing = high_ - low_;
    return fmt::format(
        "low {:.4g} V, high {:.4g} V, swing {:.4g} V, rise (10-90 %) {}, fall {}, overshoot "
        "{:.0f} % of the swing, {} reversals inside the hysteresis band",
        low_, high_, swing, spread(rises_), spread(falls_), swing > 0 ? 100 * over_ / swing : 0.0,
        reversals);
}

}  // namespace busdecode
