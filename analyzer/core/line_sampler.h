#pragma once
// Samples one line at chosen moments that may lie *ahead* of the edge being processed:
// BiSS-C samples SL at MA rise + line delay + T/2, a UART samples mid-bit from the start
// edge, SSI can sample a delayed data line. Decoders schedule sample times, feed the
// line's edges and the passing of time, and pop resolved samples in order.
#include <cstddef>
#include <cstdint>
#include <vector>

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
        buf_.clear();
        head_ = resolved_ = 0;
    }
    // Schedules a sample at tick t (fractional ticks allowed). Times must not decrease.
    void schedule(double t, std::uint32_t tag) { buf_.push_back({t, tag, false}); }
    // Drops the samples not resolved yet (resolved ones can still be popped).
    void cancelAll() {
        if (head_ == resolved_) {  // nothing left to pop either: empty (see empty())
            buf_.clear();
            head_ = resolved_ = 0;
        } else {
            buf_.resize(resolved_);
        }
    }

    // An edge of the sampled line at t: samples strictly before t see the old level.
    void lineEdge(Tick t, bool level) {
        resolveBefore(double(t));
        level_ = level;
    }
    // An edge of the sampled line while the sampler is empty(): lineEdge() without a
    // sample to resolve, so without the time (BiSS-C sets the level once per run of edges).
    void setLevel(bool level) { level_ = level; }
    // No edge on the sampled line before `now`: samples before it see the current level.
    void advanceTo(Tick now) { resolveBefore(double(now)); }
    // End of capture: resolves every remaining sample with the current level.
    void flush() { resolveBefore(1e300); }

    bool ready() const { return head_ < resolved_; }
    // Nothing to pop and nothing pending: !ready() && pending() == 0 in one test. The
    // buffer is emptied whenever that holds (pop(), cancelAll(), reset()).
    bool empty() const { return buf_.empty(); }
    Sample pop() {
        // Field by field: a whole-struct copy loads `level` inside a wider word just
        // after resolveBefore() stored it as a byte, and that store cannot be forwarded
        // to the load (a stall per sample: a fifth of the samples in BiSS-C's onMa, by
        // perf annotate, before this was read field by field).
        const Sample& b = buf_[head_++];
        const Sample s{b.t, b.tag, b.level};
        if (head_ == buf_.size()) {
            buf_.clear();
            head_ = resolved_ = 0;
        } else if (head_ >= kCompactAt && head_ == resolved_) {
            buf_.erase(buf_.begin(), buf_.begin() + std::ptrdiff_t(head_));
            head_ = resolved_ = 0;
        }
        return s;
    }
    bool level() const { return level_; }
    std::size_t pending() const { return buf_.size() - resolved_; }
    // Time of the earliest unresolved sample (only valid when pending() > 0).
    double nextTime() const { return buf_[resolved_].t; }

private:
    // One buffer, in time order: [head_, resolved_) resolved and not popped yet,
    // [resolved_, end) scheduled. Emptied whenever everything is popped (the usual case,
    // once per frame), compacted if a decoder keeps samples pending for long.
    static constexpr std::size_t kCompactAt = 4096;

    void resolveBefore(double t) {
        while (resolved_ < buf_.size() && buf_[resolved_].t < t)
            buf_[resolved_++].level = level_;
    }
    bool level_ = true;
    std::vector<Sample> buf_;
    std::size_t head_ = 0, resolved_ = 0;
};

}  // namespace busdecode
