#pragma once
// Emptied events shared between threads: the decoding thread's output hands the events it
// is done with back here, and the threads decoding pieces ahead (piece_speculation.h) take
// them to fill again. An event's strings and vectors keep their storage, so that a frame
// costs no allocation on the thread that builds it and no free (across threads, the
// dearest kind) on the one that outputs it. In batches, one lock each.
#include <algorithm>
#include <cstddef>
#include <mutex>
#include <utility>
#include <vector>

#include "event.h"

namespace busdecode {

class EventPool {
public:
    // Events held at most: about 2 MB. Beyond that, what is given back is freed.
    static constexpr std::size_t kMaxHeld = 4096;

    // Moves up to `n` events into `out` (appended); none if the pool is empty.
    void take(std::vector<EventPtr>& out, std::size_t n) {
        std::lock_guard<std::mutex> lock(m_);
        const std::size_t k = std::min(n, held_.size());
        for (std::size_t i = 0; i < k; ++i) {
            out.push_back(std::move(held_.back()));
            held_.pop_back();
        }
    }
    // Takes the events in `in` (emptied: reset() already called on each), leaving `in`
    // empty; those beyond kMaxHeld are freed.
    void give(std::vector<EventPtr>& in) {
        {
            std::lock_guard<std::mutex> lock(m_);
            while (!in.empty() && held_.size() < kMaxHeld) {
                held_.push_back(std::move(in.back()));
                in.pop_back();
            }
        }
        in.clear();
    }

private:
    std::mutex m_;
    std::vector<EventPtr> held_;
};

}  // namespace busdecode
