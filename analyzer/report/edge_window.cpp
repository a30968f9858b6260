#include "edge_window.h"

#include <algorithm>

namespace busdecode {

void EdgeWindows::begin(const CaptureFacts& facts) {
    bindings_ = facts.bindings;
    int lines = 0;
    for (const auto& b : bindings_)
        lines = std::max(lines, b.line + 1);
    rings_.assign(std::size_t(lines), {});
    volts_.assign(std::size_t(lines), {});
    waves_.clear();
    faulty_taken_.clear();
    clean_taken_.clear();
}

void EdgeWindows::addEdges(const Edge* first, const Edge* last) {
    for (; first != last; ++first)
        if (first->line < rings_.size()) rings_[first->line].push({first->t, first->level});
}

void EdgeWindows::addVolts(const std::vector<VoltSample>& volts,
                           const std::vector<LineThreshold>& thresholds) {
    for (const LineThreshold& th : thresholds)
        if (th.line < volts_.size()) volts_[th.line].trigger = th;
    for (const VoltSample& v : volts)
        if (v.line < volts_.size()) volts_[v.line].samples.push({v.t, v.volts});
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
    const auto& r = rings_[std::size_t(line)];
    bool seen_before = false;
    for (std::size_t k = 0; k < r.size(); ++k) {
        const auto& [t, level] = r[k];
        if (t < from) {
            out.level_before = level;
            seen_before = true;
        } else if (t <= to && out.edges.size() < kMaxEdgesPerLine) {
            out.edges.emplace_back(t, level);
        }
    }
    // The ring was full and started after `from`: the level before is a guess.
    if (!seen_before && r.full()) out.complete = false;
    if (!seen_before && !out.edges.empty()) out.level_before = !out.edges.front().second;
    copyTrace(line, from, to, out);
    return out;
}

void EdgeWindows::copyTrace(int line, Tick from, Tick to, LineWave& out) const {
    const VoltRing& r = volts_[std::size_t(line)];
    if (!r.trigger) return;
    out.analog = true;
    out.threshold = r.trigger->threshold;
    out.hysteresis = r.trigger->hysteresis;
    out.trace_complete = !(r.samples.full() && r.samples.size() && r.samples[0].first > from);
    // The lowest and highest sample of each column, in the order they came.
    const double per_column = double(to - from + 1) / double(kTraceColumns);
    std::size_t column = 0, lo = 0, hi = 0, count = 0;
    auto flush = [&] {
        if (!count) return;
        const std::size_t a = std::min(lo, hi), b = std::max(lo, hi);
        out.trace.push_back(r.samples[a]);
        if (b != a) out.trace.push_back(r.samples[b]);
        count = 0;
    };
    for (std::size_t k = 0; k < r.samples.size(); ++k) {
        const auto& [t, v] = r.samples[k];
        if (t < from || t > to) continue;
        const auto c = std::size_t(double(t - from) / per_column);
        if (count && c != column) flush();
        if (!count) {
            column = c;
            lo = hi = k;
        }
        if (v < r.samples[lo].second) lo = k;
        if (v > r.samples[hi].second) hi = k;
        ++count;
    }
    flush();
}

}  // namespace busdecode
