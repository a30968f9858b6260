#pragma once
// The captured waveform of a few chosen events, kept while the capture streams by: a ring
// of the most recent edges per mapped line (fixed size), and, when an event worth drawing
// arrives (the first faulty ones of each decoder, and a clean one of each event type for
// comparison), the edges around it copied out of the rings. Memory stays flat however
// long the capture.
#include <cstdint>
#include <map>
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
};

struct FrameWave {
    Event event;
    Tick from = 0, to = 0;  // the window drawn: the event with some margin
    bool faulty = false;
    std::vector<LineWave> lines;  // the event's decoder's lines, in role order
};

class EdgeWindows {
public:
    static constexpr std::size_t kRingEdges = std::size_t(1) << 15;  // per line
    static constexpr std::size_t kMaxEdgesPerLine = 4096;            // per drawn event
    static constexpr std::size_t kFaultyPerInstance = 2;

    void begin(const CaptureFacts& facts);
    void addEdges(const Edge* first, const Edge* last);
    // Keeps the event's waveform when it is one to draw.
    void offer(const Event& e);
    const std::vector<FrameWave>& waves() const { return waves_; }

private:
    struct Ring {
        std::vector<Tick> t;
        std::vector<std::uint8_t> level;
        std::size_t next = 0, size = 0;
    };
    FrameWave capture(const Event& e, bool faulty) const;
    LineWave copyLine(int line, Tick from, Tick to) const;

    std::vector<Ring> rings_;  // by Edge::line
    std::vector<CaptureFacts::Binding> bindings_;
    std::map<std::string, std::size_t> faulty_taken_;  // per instance
    std::map<std::string, bool> clean_taken_;          // per "instance/type"
    std::vector<FrameWave> waves_;
};

}  // namespace busdecode
