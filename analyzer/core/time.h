#pragma once
// Capture time: every edge and event is an int64 tick count in the capture's own
// timebase (VCD timescale unit, or one sample for dense CSV and .sr). Keeping ticks
// exact means sample indices compare 1:1 with sigrok's expected outputs.
#include <cstdint>
#include <limits>

namespace busdecode {

using Tick = std::int64_t;
inline constexpr Tick kNoTick = std::numeric_limits<Tick>::min();

// One tick lasts num/den seconds (e.g. 1/24'000'000 for a 24 MHz sample, 1/10^10 for
// a 100 ps VCD timescale). Rational so that neither form loses precision.
struct Timebase {
    static constexpr std::int64_t kNsPerSecond = 1'000'000'000;
    std::int64_t num = 1;
    std::int64_t den = 1'000'000'000;

    static Timebase fromSampleRate(std::int64_t hz) { return Timebase{1, hz}; }
    double secondsPerTick() const { return double(num) / double(den); }
    double nsPerTick() const { return secondsPerTick() * 1e9; }
    double ticksPerNs() const { return 1.0 / nsPerTick(); }
    // Exact for every realistic capture length (128-bit intermediate).
    std::int64_t toNs(Tick t) const {
        // A whole number of ns per tick (every sample rate dividing 1 GHz, VCD units of
        // 1 ns and up): one multiplication, not a 128-bit division per event.
        if (num > 0 && den > 0 && num <= kNsPerSecond && (num * kNsPerSecond) % den == 0) {
            std::int64_t ns;
            if (!__builtin_mul_overflow(t, num * kNsPerSecond / den, &ns)) return ns;
        }
        __int128 v;
        if (__builtin_mul_overflow((__int128)t, (__int128)num * 1'000'000'000, &v))
            return (t < 0) == (num < 0) ? std::numeric_limits<std::int64_t>::max()
                                        : std::numeric_limits<std::int64_t>::min();
        __int128 q = v / den, r = v % den;
        if (2 * (r < 0 ? -r : r) >= den) q += (v < 0 ? -1 : 1);  // round half away from zero
        // Saturated beyond +-292 years (a coarse timebase with huge tick counts).
        if (q > std::numeric_limits<std::int64_t>::max())
            return std::numeric_limits<std::int64_t>::max();
        if (q < std::numeric_limits<std::int64_t>::min())
            return std::numeric_limits<std::int64_t>::min();
        return (std::int64_t)q;
    }
    double toNsF(double ticks) const { return ticks * nsPerTick(); }
    double fromNs(double ns) const { return ns * ticksPerNs(); }
    double fromSeconds(double s) const { return s / secondsPerTick(); }
    double sampleRateHz() const { return double(den) / double(num); }
};

}  // namespace busdecode
