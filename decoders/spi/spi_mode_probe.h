#pragma once
// Tells the SPI mode from the first edges of the traffic, to check the one given: the
// data lines change after the shifting clock edge (so the other edge samples), and the
// clock rests at CPOL when chip select asserts. Looks at the first kEdges edges only, so
// it costs nothing on a long capture.
#include <cstdint>
#include <optional>

#include "core/time.h"

namespace busdecode {

class SpiModeProbe {
public:
    static constexpr std::uint64_t kEdges = 4096;
    // Roles as in spi_info.h; `levels`: one bit per role at the start.
    void start(unsigned levels, bool cs_bound, bool cs_active_high);
    bool wants() const { return seen_ < kEdges; }
    void edge(Tick t, int role, bool level);

    struct Finding {
        bool sample_rising = true;                // data changes after falling edges
        std::optional<int> cpol;                  // the clock's level at chip select, when it tells
        std::uint64_t changes = 0, agreeing = 0;  // data changes classified, and agreeing
    };
    // What the traffic says, when enough data changes agree (nine in ten of 16 or more).
    std::optional<Finding> finding() const;

private:
    void attribute(std::uint64_t n, int clock_rose);

    std::uint64_t seen_ = 0;
    bool sclk_ = false, cs_active_ = true, cs_bound_ = false, cs_active_high_ = false;
    int last_clock_rose_ = -1;  // the last clock edge since chip select: 1 rising, 0 falling
    Tick last_clock_t_ = kNoTick;
    Tick pending_t_ = kNoTick;  // data changes since that clock edge, at this tick
    std::uint64_t pending_ = 0;
    std::uint64_t after_rising_ = 0, after_falling_ = 0;
    std::uint64_t idle_high_ = 0, idle_low_ = 0;
};

}  // namespace busdecode
