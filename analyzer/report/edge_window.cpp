#include "edge_window.h"

#include <algorithm>

namespace busdecode {

void EdgeWindows::begin(const CaptureFacts& facts) {
    bindings_ = facts.bindings;
    int lines = 0;
    for (const auto& b : bindings_)
        lines = std::max(lines, b.line + 1);
    rings_.assign(std::size_t(lines), Ring{});
    waves_.clear();
    faulty_taken_.clear();
    clean_taken_.clear();
}

void EdgeWindows::addEdges(const Edge* first, const Edge* last) {
    for (; first != last; ++first) {
        if (first->line >= rings_.size()) continue;
        Ring& r = rings_[first->line];
        if (r.t.empty()) {
            r.t.resize(kRingEdges);
            r.level.resize(kRingEdges);
        }
        r.t[r.next] = first->t;
        r.level[r.next] = first->level;
        r.next = (r.next + 1) % kRingEdges;
        r.size = std::min(r.size + 1, kRingEdges);
    }
}

void EdgeWindows::offer(const Event& e) {
    if (e.end <= e.start) return;  // a moment (a summary) has no waveform of its own
    const std::string& inst = e.instance.empty() ? e.proto : e.instance;
    if (!e.errors.empty()) {
        if (faulty_taken_[inst] >= kFaultyPerInstance) return;
        ++faulty_taken_[inst];
        waves_.push_back(capture(e, true));
        return;
    }
    bool& taken = clean_taken_[inst + "/" + e.type];
    if (taken) return;
    taken = true;
    waves_.push_back(capture(e, false));
}

FrameWave EdgeWindows::capture(const Event& e, bool faulty) const {
    FrameWave w;
    w.event = e;
    w.faulty = faulty;
    const Tick span = std::max<Tick>(e.end - e.start, 1);
    w.from = e.start - span / 8 - 1;
    w.to = e.end + span / 8 + 1;
    const std::string& inst = e.instance.empty() ? e.proto : e.instance;
    for (const auto& b : bindings_) {
        if (b.instance != inst || b.line < 0) continue;
        LineWave lw = copyLine(b.line, w.from, w.to);
        lw.role = b.role;
        lw.signal = b.signal;
        w.lines.push_back(std::move(lw));
    }
    return w;
}

LineWave EdgeWindows::copyLine(int line, Tick from, Tick to) const {
    LineWave out;
    const Ring& r = rings_[std::size_t(line)];
    const std::size_t oldest = (r.next + kRingEdges - r.size) % kRingEdges;
    bool seen_before = false;
    for (std::size_t k = 0; k < r.size; ++k) {
        const std::size_t i = (oldest + k) % kRingEdges;
        const Tick t = r.t[i];
        if (t < from) {
            out.level_before = r.level[i];
            seen_before = true;
        } else if (t <= to && out.edges.size() < kMaxEdgesPerLine) {
            out.edges.emplace_back(t, r.level[i]);
        }
    }
    // The ring was full and started after `from`: the level before is a guess.
    if (!seen_before && r.size == kRingEdges) out.complete = false;
    if (!seen_before && !out.edges.empty()) out.level_before = !out.edges.front().second;
    return out;
}

}  // namespace busdecode
