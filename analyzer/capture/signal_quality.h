#pragma once
// Signal quality of an analog line, measured as its samples stream by, in constant
// memory: rise and fall times (10-90 % of the swing between the line's two levels; median
// and 99th percentile from a bounded reservoir of them), the largest overshoot beyond
// either level, and how often the signal turned back inside the hysteresis band.
#include <algorithm>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "core/event.h"

namespace busdecode {

// Durations in ns; NaN where no edge was seen.
struct SignalFigures {
    double low_v = 0, high_v = 0, swing_v = 0, overshoot_pct = 0;
    double rise_median_ns = 0, rise_p99_ns = 0, fall_median_ns = 0, fall_p99_ns = 0;
    std::uint64_t rises = 0, falls = 0;
};

class SignalQuality {
public:
    // `low` and `high`: the line's levels (volts).
    void configure(double low, double high) {
        low_ = low;
        high_ = high;
        const double swing = high - low;
        at10_ = low + 0.1 * swing;
        at90_ = low + 0.9 * swing;
    }
    // A sample (time in seconds).
    void feed(double t, double v) {
        if (have_) {
            crossing(t, v, at10_, true, rise_from_);
            crossing(t, v, at90_, false, fall_from_);
            if (v >= at90_ && prev_v_ < at90_ && rise_from_ >= 0)
                keep(rises_, at(t, v, at90_) - rise_from_, rise_count_), rise_from_ = -1;
            if (v <= at10_ && prev_v_ > at10_ && fall_from_ >= 0)
                keep(falls_, at(t, v, at10_) - fall_from_, fall_count_), fall_from_ = -1;
        }
        over_ = std::max(over_, std::max(v - high_, low_ - v));
        prev_t_ = t;
        prev_v_ = v;
        have_ = true;
    }
    // The next sample follows a stretch not recorded: no edge is measured across it.
    void restart() {
        have_ = false;
        rise_from_ = fall_from_ = -1;
    }
    // "low 0.02 V, high 3.28 V, swing 3.26 V, rise (10-90 %) median 41 ns p99 55 ns, ..."
    // with the trigger's count of reversals inside its band.
    std::string summary(std::uint64_t reversals) const;
    SignalFigures figures() const;
    // The line's `signal` event (proto "capture"), times left to the caller.
    Event event(const std::string& line, double threshold, double hysteresis,
                std::uint64_t reversals) const;

private:
    static constexpr std::size_t kKept = 4096;
    double at(double t, double v, double level) const {
        return prev_t_ + (t - prev_t_) * (level - prev_v_) / (v - prev_v_);
    }
    // Starts an edge's measurement where the signal leaves the far level's 10 (90) % line.
    void crossing(double t, double v, double level, bool upward, double& from) {
        if (upward ? (prev_v_ <= level && v > level) : (prev_v_ >= level && v < level))
            from = at(t, v, level);
    }
    void keep(std::vector<double>& kept, double d, std::uint64_t& count) {
        ++count;
        if (kept.size() < kKept)
            kept.push_back(d);
        else if (const auto j = std::uint64_t(rng_() % count); j < kKept)
            kept[j] = d;  // a uniform sample of all of them (reservoir)
    }
    double low_ = 0, high_ = 0, at10_ = 0, at90_ = 0;
    double prev_t_ = 0, prev_v_ = 0, rise_from_ = -1, fall_from_ = -1, over_ = 0;
    bool have_ = false;
    std::vector<double> rises_, falls_;
    std::uint64_t rise_count_ = 0, fall_count_ = 0;
    std::minstd_rand rng_{1};
};

}  // namespace busdecode
