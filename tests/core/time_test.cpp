// Timebase::toNs: the one-multiplication path for whole ns per tick must give what the
// exact 128-bit rational conversion gives, rounding and saturation included.
#include <cstdint>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include "core/time.h"

namespace busdecode {
namespace {

// The reference: ticks * num / den seconds in ns, rounded half away from zero,
// saturated to int64.
std::int64_t exactNs(const Timebase& tb, Tick t) {
    const __int128 v = (__int128)t * tb.num * 1'000'000'000;
    __int128 q = v / tb.den;
    const __int128 r = v % tb.den;
    if (2 * (r < 0 ? -r : r) >= tb.den) q += v < 0 ? -1 : 1;
    if (q > std::numeric_limits<std::int64_t>::max())
        return std::numeric_limits<std::int64_t>::max();
    if (q < std::numeric_limits<std::int64_t>::min())
        return std::numeric_limits<std::int64_t>::min();
    return std::int64_t(q);
}

TEST(Timebase, ToNsMatchesTheExactConversion) {
    const std::vector<Timebase> bases = {
        {1, 1'000'000'000},      // VCD 1 ns
        {1, 100'000'000},        // 100 MS/s: 10 ns per tick (the fast path)
        {1, 1'000},              // VCD 1 ms
        {1, 1},                  // VCD 1 s
        {10, 1},                 // VCD 10 s
        {1, 24'000'000},         // 24 MS/s: not a whole number of ns
        {1, 10'000'000'000},     // VCD 100 ps
        {1, 1'000'000'000'000},  // VCD 1 ps
        {1'000'000, 3'000'000'000'000},
        {3, 7},
    };
    const std::vector<Tick> ticks = {0,
                                     1,
                                     -1,
                                     7,
                                     -13,
                                     123'456'789,
                                     -987'654'321'012,
                                     std::numeric_limits<Tick>::max() / 10,
                                     std::numeric_limits<Tick>::max() / 10 + 1,
                                     std::numeric_limits<Tick>::max(),
                                     std::numeric_limits<Tick>::min() + 1,
                                     std::numeric_limits<Tick>::min()};
    for (const auto& tb : bases)
        for (Tick t : ticks)
            EXPECT_EQ(tb.toNs(t), exactNs(tb, t)) << tb.num << "/" << tb.den << " tick " << t;
}

TEST(Timebase, ToNsSaturatesFarOutOfRange) {
    const Timebase ten_ns{1, 100'000'000};
    EXPECT_EQ(ten_ns.toNs(std::numeric_limits<Tick>::max()),
              std::numeric_limits<std::int64_t>::max());
    EXPECT_EQ(ten_ns.toNs(std::numeric_limits<Tick>::min()),
              std::numeric_limits<std::int64_t>::min());
    EXPECT_EQ(ten_ns.toNs(-5), -50);
}

}  // namespace
}  // namespace busdecode
