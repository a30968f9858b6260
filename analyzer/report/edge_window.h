#pragma once
// The captured waveform of a few chosen events, kept while the capture streams by: a ring
// of the most recent edges per mapped line (fixed size), and, when an event worth drawing
// arrives (the first faulty ones of each decoder, and a clean one of each event type for
// comparison), the edges around it copied out of the rings. Memory stays flat however
// long the capture. Analog lines keep a ring of their recent samples too.
#include <algorithm>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/edge.h"
#include "core/event.h"
#include "core/session.h"

namespace busdecode {

struct LineWave {
    std::string role, signal;
    int level_before = 1;                              // level at `from` (before the first edge)
    std::vector<std::pair<Tick, std::uint8_t>> edges;  // in [from, to], time order
    bool complete = true;  // false: the ring had already dropped edges this early
    // An analog line: its voltage as sampled in [from, to] (the lowest and highest sample
    // of each drawn column, in time order) and the trigger its edges come from.
    std::vector<std::pair<Tick, float>> trace;
    bool analog = false, trace_complete = true;
    float threshold = 0, hysteresis = 0;
};

struct FrameWave {
    Event event;
    Tick from = 0, to = 0;  // the window drawn: the event with some margin
    bool faulty = false;
    std::vector<LineWave> lines;  // the event's decoder's lines, in role order
};

// The most recent `N` values pushed, oldest dropped first; storage taken at the first push.
template <typename T, std::size_t N>
class RecentRing {
public:
    void push(const T& v) {
        if (items_.empty()) items_.resize(N);
        items_[next_] = v;
        next_ = (next_ + 1) % N;
        size_ = std::min(size_ + 1, N);
    }
    std::size_t size() const { return size_; }
    bool full() const { return size_ == N; }
    // The k-th oldest kept value.
    const T& operator[](std::size_t k) const { return items_[(next_ + N - size_ + k) % N]; }

private:
    std::vector<T> items_;
    std::size_t next_ = 0, size_ = 0;
};

class EdgeWindows {
public:
    static constexpr std::size_t kRingEdges = std::size_t(1) << 15;  // per line
    static constexpr std::size_t kRingVolts = std::size_t(1) << 16;  // per analog line
    static constexpr std::size_t kMaxEdgesPerLine = 4096;            // per drawn event
    static constexpr std::size_t kTraceColumns = 960;                // min and max kept per column
    static constexpr std::size_t kFaultyPerInstance = 2;

    void begin(const CaptureFacts& facts);
    void addEdges(const Edge* first, const Edge* last);
    void addVolts(const std::vector<VoltSample>& volts,
                  const std::vector<LineThreshold>& thresholds);
    // Keeps the event's waveform when it is one to draw.
    void offer(const Event& e);
    const std::vector<FrameWave>& waves() const { return waves_; }

private:
    struct VoltRing {
        RecentRing<std::pair<Tick, float>, kRingVolts> samples;
        std::optional<LineThreshold> trigger;
    };
    FrameWave capture(const Event& e, bool faulty) const;
    LineWave copyLine(int line, Tick from, Tick to) const;
    void copyTrace(int line, Tick from, Tick to, LineWave& out) const;

    std::vector<RecentRing<std::pair<Tick, std::uint8_t>, kRingEdges>> rings_;  // by Edge::line
    std::vector<VoltRing> volts_;                                               // by Edge::line
    std::vector<CaptureFacts::Binding> bindings_;
    std::map<std::string, std::size_t> faulty_taken_;  // per instance
    std::map<std::string, bool> clean_taken_;          // per "instance/type"
    std::vector<FrameWave> waves_;
};

}  // namespace busdecode
