#pragma once
// Samples one line at chosen moments that may lie *ahead* of the edge being processed:
// BiSS-C samples SL at MA rise + line delay + T/2, a UART samples mid-bit from the start
// edge, SSI can sample a delayed data line. Decoders schedule sample times, feed the
// line's edges and the passing of time, and pop resolved samples in order.
#include <cstdint>
#include <deque>

#include "time.h"

namespace busdecode {

class LineSampler {
public:
    struct Sample {
        double t;
        std::uint32_t tag;
        bool level;
    };

    void reset(bool level) {
        level_ = level;
        queue_.clear();
        ready_.clear();
    }
    // Schedules a sample at tick t (fractional ticks allowed). Times must not decrease.
    void schedule(double t, std::uint32_t tag) { queue_.push_back({t, tag, false}); }
    void cancelAll() { queue_.clear(); }

    // An edge of the sampled line at t: samples strictly before t see the old level.
    void lineEdge(Tick t, bool level) {
        resolveBefore(double(t));
        level_ = level;
    }
    // No edge on the sampled line before `now`: samples before it see the current level.
    void advanceTo(Tick now) { resolveBefore(double(now)); }
    // End of capture: resolves every remaining sample with the current level.
    void flush() { resolveBefore(1e300); }

    bool ready() const { return !ready_.empty(); }
    Sample pop() {
        Sample s = ready_.front();
        ready_.pop_front();
        return s;
    }
    bool level() const { return level_; }
    std::size_t pending() const { return queue_.size(); }
    // Time of the earliest unresolved sample (only valid when pending() > 0).
    double nextTime() const { return queue_.front().t; }

private:
    void resolveBefore(double t) {
        while (!queue_.empty() && queue_.front().t < t) {
            Sample s = queue_.front();
            queue_.pop_front();
            s.level = level_;
            ready_.push_back(s);
        }
    }
    bool level_ = true;
    std::deque<Sample> queue_;
    std::deque<Sample> ready_;
};

}  // namespace busdecode
