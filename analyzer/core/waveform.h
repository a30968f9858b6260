#pragma once
// A capture held in memory: what the signal generators beside each decoder produce,
// and what the writers turn into VCD / CSV files. Generators describe each line's
// levels over time; build() merges the lines into one time-ordered edge list.
#include <cstdint>
#include <string>
#include <vector>

#include "edge.h"
#include "time.h"

namespace busdecode {

struct Waveform {
    Timebase timebase;
    std::vector<std::string> names;
    std::vector<std::uint8_t> initial;  // level of each line before the first edge
    std::vector<Edge> edges;            // time ordered, `line` indexes names
    Tick start = 0;                     // capture start (first sample)
    Tick end = 0;                       // capture end (>= last edge)
};

class WaveBuilder {
public:
    WaveBuilder(Timebase tb, std::vector<std::string> names, std::vector<std::uint8_t> initial);
    // Drives `line` to `level` from tick t on. Times per line must not decrease; a call
    // that does not change the level adds nothing; two changes at the same tick cancel.
    void set(std::uint32_t line, Tick t, bool level);
    // Same, with the time in nanoseconds (rounded to the nearest tick).
    void setNs(std::uint32_t line, double ns, bool level);
    bool level(std::uint32_t line) const { return levels_[line]; }
    Tick lastTick() const { return last_; }
    const Timebase& timebase() const { return tb_; }
    std::size_t lineCount() const { return levels_.size(); }
    // Merges the lines; `end` is the capture end (at least the last edge).
    Waveform build(Tick end) const;
    Tick ticksFromNs(double ns) const;

private:
    Timebase tb_;
    std::vector<std::string> names_;
    std::vector<std::uint8_t> initial_;
    std::vector<std::uint8_t> levels_;
    std::vector<std::vector<Edge>> per_line_;
    Tick last_ = 0;
};

// Appends the lines of `b` to `a` (same timebase required): two buses in one capture.
Waveform mergeWaveforms(const Waveform& a, const Waveform& b);

}  // namespace busdecode
