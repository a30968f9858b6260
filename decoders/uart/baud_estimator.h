#pragma once
// Guesses the bit rate of asynchronous serial traffic from the shortest pulse on its
// lines (`baud=auto`): in ordinary traffic some pulse is one bit long. The estimate is
// refined over every pulse that is a whole number of bits long, then snapped to a
// standard rate when one is within a few percent.
#include <optional>
#include <vector>

#include "core/time.h"

namespace busdecode {

class BaudEstimator {
public:
    explicit BaudEstimator(int lines) : last_(lines, kNoTick) {}
    // An edge on `line` at tick t (edges of one line in time order).
    void addEdge(Tick t, int line);
    std::size_t pulses() const { return widths_.size(); }
    // Bits per second, or nothing when no pulse was seen.
    std::optional<double> measuredBaud(const Timebase& tb) const;
    // The nearest standard rate when within 4 %, else the measured rate.
    static double snapToStandard(double baud);

private:
    std::vector<Tick> last_;
    std::vector<Tick> widths_;
};

}  // namespace busdecode
