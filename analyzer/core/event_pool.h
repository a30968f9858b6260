#pragma once
// Emptied events for decoders to fill again. EventPool is shared between threads: the
// decoding thread's output hands the events it is done with back there, and the threads
// decoding pieces ahead (piece_speculation.h) take them to fill again, so that a frame
// costs no allocation on the thread that builds it and no free (across threads, the
// dearest kind) on the one that outputs it; in batches, one lock each. RecycledEvents is
// one thread's own store in front of it.
#include <algorithm>
#include <cstddef>
#include <mutex>
#include <utility>
#include <vector>

#include "event.h"

namespace busdecode {

// Whose storage an event is, for the session to give it back to once output: 0, the
// decoding thread's; 1, a reader thread's (RecycledEvents::sendHome()). Kept in the event
// (a side table would cost a look-up per event, shared between threads), out of its
// interface.
class EventHome {
public:
    static std::uint8_t of(const Event& e) { return e.home_; }
    static void set(Event& e, std::uint8_t home) { e.home_ = home; }
};

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
    // Takes the events in `in` (emptied by reset(), or with EventHome 1, to be emptied
    // by the store that takes them), leaving `in` empty; those beyond kMaxHeld are freed.
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

// One thread's emptied events, for its decoders to fill again: their strings and vectors
// keep their storage (two allocations and frees per event otherwise). It holds up to
// `keep`; with a shared pool, it takes from it when it has none and gives it what it
// cannot hold, kBatch at a time, and gives back what it holds at the end.
//
// Events another thread filled (EventHome 1) can go back to that thread's pool as
// they are, not emptied (sendHome()): that thread empties them when it takes them
// (fresh()). Then this thread only reads their storage. Storage written on one
// core and then on the other must cross between them each time, and on a VM whose two
// cores may sit on two dies that crossing is slow (bench/README.md, "Two dies").
class RecycledEvents {
public:
    static constexpr std::size_t kBatch = 256;

    explicit RecycledEvents(std::size_t keep, EventPool* shared = nullptr)
        : keep_(keep), shared_(shared) {}
    ~RecycledEvents() {
        if (shared_) {
            shared_->give(overflow_);
            shared_->give(held_);
        }
        if (home_) home_->give(to_home_);
    }
    RecycledEvents(const RecycledEvents&) = delete;
    RecycledEvents& operator=(const RecycledEvents&) = delete;

    void setShared(EventPool* shared) { shared_ = shared; }
    // Events with home 1 go to `pool` when recycled, not emptied.
    void sendHome(EventPool* pool) { home_ = pool; }

    // An empty event to fill.
    EventPtr fresh() {
        if (held_.empty() && shared_) shared_->take(held_, kBatch);
        if (held_.empty()) return std::make_unique<Event>();
        EventPtr e = std::move(held_.back());
        held_.pop_back();
        if (EventHome::of(*e) == 1) e->reset();  // perhaps given back as it was (sendHome())
        return e;
    }
    // `e`'s contents in an event of this store's.
    EventPtr adopt(Event&& e) {
        EventPtr owned = fresh();
        *owned = std::move(e);
        return owned;
    }
    // An event done with: emptied and kept, handed on, or freed.
    void recycle(EventPtr e) {
        if (EventHome::of(*e) == 1 && home_) {
            to_home_.push_back(std::move(e));
            if (to_home_.size() >= kBatch) home_->give(to_home_);
        } else if (held_.size() < keep_) {
            e->reset();
            held_.push_back(std::move(e));
        } else if (shared_) {
            e->reset();
            overflow_.push_back(std::move(e));
            if (overflow_.size() >= kBatch) shared_->give(overflow_);
        }
    }

private:
    const std::size_t keep_;
    EventPool* shared_;
    EventPool* home_ = nullptr;
    std::vector<EventPtr> held_, overflow_, to_home_;
};

}  // namespace busdecode
