#pragma once
// The reports' signal-quality section: a row per analog line from its `signal` event
// (levels, swing, threshold, edge times, overshoot, reversals), the pair faults seen, a
// live run's gaps of dropped samples and a sequence capture's dead times between its
// segments, as text and as HTML. A logic capture read whole
// has none of them: the section is then left out.
#include <cstdint>
#include <string>
#include <vector>

#include "core/event.h"
#include "core/time.h"

namespace busdecode {

class SignalSection {
public:
    static constexpr std::size_t kMaxLines = 64;
    static constexpr std::size_t kMaxFaults = 10;

    // Takes the capture layer's events (proto "capture"); true if `e` was one.
    bool add(const Event& e, const Timebase& tb);
    bool empty() const {
        return lines_.empty() && faults_.count == 0 && gaps_.count == 0 && segment_gaps_.count == 0;
    }
    std::string text() const;
    std::string html() const;

private:
    // The table's cells, formatted once: line, low, high, swing, threshold, hysteresis,
    // rise median/p99, fall median/p99, overshoot, reversals.
    std::vector<std::vector<std::string>> lines_;
    // Stretches of one kind: how many, and the first kMaxFaults as lines
    // ("1.234 ms to 5.678 ms: SUMMARY").
    struct Stretches {
        std::uint64_t count = 0;
        std::vector<std::string> first;
        void add(const Event& e, const Timebase& tb);
    };
    Stretches faults_, gaps_, segment_gaps_;  // pair faults, live gaps, segment gaps
    std::uint64_t dropped_samples_ = 0;
    std::string gapsHeading() const;
    std::string segmentGapsHeading() const;
};

}  // namespace busdecode
