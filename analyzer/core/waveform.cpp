#include "waveform.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace busdecode {

WaveBuilder::WaveBuilder(Timebase tb, std::vector<std::string> names,
                         std::vector<std::uint8_t> initial)
    : tb_(tb), names_(std::move(names)), initial_(std::move(initial)) {
    if (names_.size() > kMaxSelectedLines)  // an Edge names at most that many lines
        throw std::length_error("WaveBuilder: more than kMaxSelectedLines lines");
    if (initial_.size() != names_.size()) initial_.resize(names_.size(), 1);
    levels_ = initial_;
    per_line_.resize(names_.size());
}

Tick WaveBuilder::ticksFromNs(double ns) const {
    return Tick(std::llround(tb_.fromNs(ns)));
}

void WaveBuilder::set(std::uint32_t line, Tick t, bool level) {
    auto& edges = per_line_.at(line);
    if (!edgeTickFits(t)) throw std::out_of_range("WaveBuilder: a time an Edge cannot hold");
    if (!edges.empty() && t < edges.back().t)
        throw std::logic_error("WaveBuilder: time went backwards");
    if (levels_[line] == std::uint8_t(level)) return;
    if (!edges.empty() && edges.back().t == t) {
        edges.pop_back();  // a zero-width pulse is no pulse
    } else {
        edges.push_back({t, line, std::uint8_t(level)});
    }
    levels_[line] = std::uint8_t(level);
    last_ = std::max(last_, t);
}

void WaveBuilder::setNs(std::uint32_t line, double ns, bool level) {
    set(line, ticksFromNs(ns), level);
}

Waveform WaveBuilder::build(Tick end) const {
    Waveform w;
    w.timebase = tb_;
    w.names = names_;
    w.initial = initial_;
    for (const auto& e : per_line_)
        w.edges.insert(w.edges.end(), e.begin(), e.end());
    std::stable_sort(w.edges.begin(), w.edges.end(), [](const Edge& a, const Edge& b) {
        return a.t < b.t || (a.t == b.t && a.line < b.line);
    });
    w.start = 0;
    w.end = std::max(end, last_);
    return w;
}

Waveform mergeWaveforms(const Waveform& a, const Waveform& b) {
    if (a.timebase.num != b.timebase.num || a.timebase.den != b.timebase.den)
        throw std::logic_error("mergeWaveforms: different timebases");
    if (a.names.size() + b.names.size() > kMaxSelectedLines)
        throw std::length_error("mergeWaveforms: more than kMaxSelectedLines lines");
    Waveform w = a;
    const auto offset = std::uint32_t(a.names.size());
    w.names.insert(w.names.end(), b.names.begin(), b.names.end());
    w.initial.insert(w.initial.end(), b.initial.begin(), b.initial.end());
    for (Edge e : b.edges) {
        e.line += offset;
        w.edges.push_back(e);
    }
    std::stable_sort(w.edges.begin(), w.edges.end(), [](const Edge& x, const Edge& y) {
        return x.t < y.t || (x.t == y.t && x.line < y.line);
    });
    w.start = std::min(a.start, b.start);
    w.end = std::max(a.end, b.end);
    return w;
}

}  // namespace busdecode
