#pragma once
// Guesses the bit rate of asynchronous serial traffic from the shortest pulse on its
// lines (`baud=auto`): in ordinary traffic some pulse is one bit long. The estimate is
// refined over every pulse at the start bit's level that is a whole number of bits long
// (one at the idle level may hold a stop bit and an idle gap), then snapped to a standard
// rate when one is within a few percent.
#include <cstdint>
#include <optional>
#include <vector>

#include "core/time.h"

namespace busdecode {

class BaudEstimator {
public:
    // idle_high: the lines idle high (the start bit is low).
    BaudEstimator(int lines, bool idle_high) : last_(lines, kNoTick), idle_high_(idle_high) {}
    // An edge on `line` at tick t to `level` (edges of one line in time order).
    void addEdge(Tick t, int line, bool level);
    std::size_t pulses() const { return widths_.size(); }
    // Bits per second, or nothing when no pulse was seen.
    std::optional<double> measuredBaud(const Timebase& tb) const;
    // The nearest standard rate when within 4 %, else the measured rate.
    static double snapToStandard(double baud);

private:
    std::vector<Tick> last_;
    bool idle_high_;
    std::vector<Tick> widths_;
    std::vector<std::uint8_t> idle_level_;  // per width: the pulse was at the idle level
};

}  // namespace busdecode
