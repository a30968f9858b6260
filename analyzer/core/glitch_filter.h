#pragma once
// Removes pulses shorter than a width on each line before a decoder sees them
// (`glitch_ns`). An edge is held until either the opposite edge comes within the width
// (both dropped, reported as a glitch) or time has moved past it; released edges keep
// their time order across lines.
#include <deque>

#include "time.h"

namespace busdecode {

class GlitchFilter {
public:
    struct Out {
        Tick t;
        int role;
        bool level;
        bool is_glitch;  // a removed pulse starting at t (level meaningless)
    };

    explicit GlitchFilter(Tick width) : width_(width) {}

    // Feeds one edge; appends what can be delivered now to `out` (in order).
    template <class Sink>
    void push(Tick t, int role, bool level, Sink&& out) {
        release(t, out);
        for (auto it = held_.rbegin(); it != held_.rend(); ++it) {
            if (it->role != role) continue;
            if (t - it->t < width_) {
                out(Out{it->t, role, level, true});
                held_.erase(std::next(it).base());
                return;
            }
            break;
        }
        held_.push_back({t, role, level});
    }
    // Time is now `now`: delivers every held edge that can no longer be cancelled.
    template <class Sink>
    void release(Tick now, Sink&& out) {
        while (!held_.empty() && held_.front().t + width_ <= now) {
            const auto h = held_.front();
            held_.pop_front();
            out(Out{h.t, h.role, h.level, false});
        }
    }
    template <class Sink>
    void flush(Sink&& out) {
        while (!held_.empty()) {
            const auto h = held_.front();
            held_.pop_front();
            out(Out{h.t, h.role, h.level, false});
        }
    }
    // Earliest held edge (events cannot start before it), or kNoTick.
    Tick oldest() const { return held_.empty() ? kNoTick : held_.front().t; }

private:
    struct Held {
        Tick t;
        int role;
        bool level;
    };
    Tick width_;
    std::deque<Held> held_;
};

}  // namespace busdecode
