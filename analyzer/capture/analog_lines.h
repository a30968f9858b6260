#pragma once
// Analog samples to edges, for any reader of sampled voltages (scope CSVs, sigrok analog
// channels): a Schmitt trigger per line whose edges are timed where the signal crosses
// the threshold, interpolated between the two samples around the crossing, so edges
// come out finer than the sample grid. Thresholds are given or found from a bounded
// prefix of the samples (the two main levels of the line); memory stays constant.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/edge.h"

namespace busdecode {

struct SchmittSettings {
    double threshold = 0;   // volts: the crossing that times an edge
    double hysteresis = 0;  // volts: the band [threshold - h/2, threshold + h/2] is ignored
    bool from_data = false;
    bool flat = false;  // from data that showed one level only: a guess
    std::optional<std::pair<double, double>> levels;  // (low, high) volts, when the data showed two
};

// Scopes write an over-range or missing sample as 9.9e37: beyond this, a value is no voltage.
inline constexpr double kNoDataVolts = 1e30;

// What a line's first samples show: its trigger settings and its two main levels.
struct LevelEstimate {
    // Threshold at the midpoint of the two levels, hysteresis a tenth of their swing. A
    // prefix with one level only gives a threshold in the middle of its range and a band
    // wider than that range (flat = true), so its noise never toggles the line.
    SchmittSettings settings;
    std::pair<double, double> levels{0, 0};  // (low, high) found
};

// The two main levels of a line from a histogram of its first samples.
class LevelEstimator {
public:
    void add(double v) {
        if (std::abs(v) <= kNoDataVolts) values_.push_back(float(v));
    }
    std::size_t size() const { return values_.size(); }
    LevelEstimate estimate() const;  // one histogram of the samples added
    void clear() { values_ = {}; }

private:
    std::vector<float> values_;
};

// One line's trigger. feed() takes samples in time order (time in ticks, fractional)
// and returns true with `edge_t` when the line changes level. An edge is timed by a
// straight line fitted to the samples within a window around the threshold (a quarter
// of the swing either side: 2.5 hysteresis bands), so noise on a slow edge averages out;
// the edge is handed out once the signal leaves that window, and a return across the
// band inside it is noise, not two edges.
class SchmittLine {
public:
    void configure(const SchmittSettings& s) {
        high_ = s.threshold + s.hysteresis / 2;
        low_ = s.threshold - s.hysteresis / 2;
        thr_ = s.threshold;
        win_ = fitWindow(s);
    }
    // The window never reaches a level: a signal that cannot leave it never hands out
    // its edge. Without known levels, the band itself is all that is known to be clear.
    static double fitWindow(const SchmittSettings& s) {
        if (!s.levels) return s.hysteresis / 2;
        const double to_low = std::abs(s.threshold - s.levels->first);
        const double to_high = std::abs(s.levels->second - s.threshold);
        return std::min({2.5 * s.hysteresis, to_low / 2, to_high / 2});
    }
    // The level before the first sample: above the threshold or not.
    std::uint8_t start(double t, double v) {
        level_ = v > thr_ ? 1 : 0;
        prev_t_ = t;
        prev_v_ = v;
        armed_ = pending_ = false;
        see(v);
        fit_ = {};
        return level_;
    }
    // A sample for minSeen() and maxSeen() only.
    void see(double v) {
        seen_min_ = v < seen_min_ ? v : seen_min_;
        seen_max_ = v > seen_max_ ? v : seen_max_;
    }
    bool feed(double t, double v, double& edge_t) {
        see(v);
        // The last crossing of the threshold towards the other level: the edge's time
        // when too few samples lie in the window to fit a line.
        const bool crossed = level_ ? (prev_v_ >= thr_ && v < thr_) : (prev_v_ <= thr_ && v > thr_);
        if (crossed && !pending_) {
            cross_t_ = prev_t_ + (t - prev_t_) * (thr_ - prev_v_) / (v - prev_v_);
            armed_ = true;
        }
        prev_t_ = t;
        prev_v_ = v;
        if (level_ ? v < low_ : v > high_) {
            level_ ^= 1;
            pending_ = !pending_;  // a second crossing inside the window undoes the first
            if (!pending_) ++reversals_;
            if (pending_) fallback_t_ = armed_ ? cross_t_ : t;
            armed_ = false;
        }
        const bool inside = std::abs(v - thr_) <= win_;
        if (inside) fit_.add(t, v);
        if (!pending_ || (inside && fit_.n < kMaxFit)) {
            if (!inside) fit_ = {};
            return false;
        }
        edge_t = fit_.crossing(thr_, fallback_t_);
        pending_ = false;
        fit_ = {};
        return true;
    }
    // The edge whose window was still open, handed out now (false: none was): the samples
    // that would have closed it were not recorded. start() then takes the next sample.
    bool flushPending(double& edge_t) {
        if (!pending_) return false;
        edge_t = fit_.crossing(thr_, fallback_t_);
        pending_ = false;
        fit_ = {};
        return true;
    }
    // No edge of this line can come before this time any more.
    double earliestNext() const {
        if (pending_) return fit_.n ? std::min(fit_.t0, fallback_t_) : fallback_t_;
        if (fit_.n) return std::min(fit_.t0, armed_ ? cross_t_ : prev_t_);
        return armed_ ? cross_t_ : prev_t_;
    }
    std::uint8_t level() const { return level_; }
    // Returns across the band while inside the window (noise or a runt pulse).
    std::uint64_t reversals() const { return reversals_; }
    double minSeen() const { return seen_min_; }
    double maxSeen() const { return seen_max_; }

private:
    static constexpr int kMaxFit = 256;
    // Least squares t = a + b v over the window's samples (t from the first of them).
    struct Fit {
        int n = 0;
        double t0 = 0, st = 0, sv = 0, svv = 0, svt = 0, last = 0;
        void add(double t, double v) {
            if (n == 0) t0 = t;
            const double x = t - t0;
            ++n;
            st += x;
            sv += v;
            svv += v * v;
            svt += v * x;
            last = t;
        }
        double crossing(double thr, double fallback) const {
            if (n < 3) return fallback;
            const double var = svv - sv * sv / n;
            if (!(var > 0)) return fallback;
            const double b = (svt - sv * st / n) / var;
            const double t = t0 + st / n + b * (thr - sv / n);
            return t < t0 ? t0 : t > last ? last : t;
        }
    };
    double thr_ = 0, high_ = 0, low_ = 0, win_ = 0;
    double prev_t_ = 0, prev_v_ = 0, cross_t_ = 0, fallback_t_ = 0;
    double seen_min_ = HUGE_VAL, seen_max_ = -HUGE_VAL;
    Fit fit_;
    bool armed_ = false, pending_ = false;
    std::uint8_t level_ = 0;
    std::uint64_t reversals_ = 0;
};

// The samples of a line whose first samples showed one level only (a guessed threshold
// in its noise), held from shortly before the signal leaves that level until enough of
// them show the line's two levels; then its edges are found in them. Memory stays
// bounded: before the signal leaves, only the last few samples are kept.
class FlatLineLearner {
public:
    // `guess`: the band the flat samples lay in (LevelEstimator's flat settings).
    void configure(const SchmittSettings& guess) {
        low_ = guess.threshold - guess.hysteresis / 2;
        high_ = guess.threshold + guess.hysteresis / 2;
    }
    // True when the held samples are enough to judge.
    bool add(double t, double v) {
        if (!departed_ && held_.size() >= 2 * kLead)
            held_.erase(held_.begin(), held_.begin() + std::ptrdiff_t(held_.size() - kLead));
        held_.push_back({t, float(v)});
        departed_ = departed_ || v < low_ || v > high_;
        return departed_ && held_.size() >= kLearn;
    }
    bool departed() const { return departed_; }
    bool idleAboveZero() const { return low_ > 0; }
    // No edge of this line can come before this time.
    double earliest(double now) const { return held_.empty() ? now : held_.front().first; }
    const std::vector<std::pair<double, float>>& held() const { return held_; }
    // The samples so far showed one level after all (a spike): wait for the next departure.
    void restart() {
        held_.erase(held_.begin(), held_.end() - std::ptrdiff_t(std::min(held_.size(), kLead)));
        departed_ = false;
    }
    void clear() { held_ = {}; }

private:
    static constexpr std::size_t kLead = 256, kLearn = 1 << 16;
    double low_ = 0, high_ = 0;
    bool departed_ = false;
    std::vector<std::pair<double, float>> held_;  // (time, volts)
};

// Edges of several lines put back in time order: a slow edge is timed at its threshold
// crossing, which may lie before an edge another line has already given.
class EdgeOrderer {
public:
    void push(Tick t, std::uint32_t line, std::uint8_t level);
    // Moves every held edge at or before `bound` into `out`, in time order.
    void release(Tick bound, std::vector<Edge>& out);
    std::size_t held() const { return held_.size(); }

private:
    std::vector<Edge> held_;  // sorted by time; a few at most
};

// "CH1=1.5" or "1.5" (--threshold) -> (signal, volts); signal empty for all lines.
// Throws InputError naming the option.
std::pair<std::string, double> parseThresholdOption(const std::string& text);
// "0.2" (--hysteresis) -> volts, 0 or more. Throws InputError naming the option.
double parseHysteresisOption(const std::string& text);

}  // namespace busdecode
