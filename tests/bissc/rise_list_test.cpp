// RiseList (decoders/bissc/rise_list.h): a frame's MA rises, appended one at a time by the
// general path and from a run's locals by BisscDecoder::dataRun(). Every rise must read
// back as written, across growth, a dropped first rise and a reused list.
#include <gtest/gtest.h>

#include <cstddef>

#include "rise_list.h"

namespace busdecode {
namespace {

TEST(RiseList, PushedRisesReadBackAcrossGrowth) {
    RiseList r;
    EXPECT_TRUE(r.empty());
    for (Tick t = 0; t < 1000; ++t)
        r.push_back(10 * t + 3);
    ASSERT_EQ(r.size(), 1000u);
    EXPECT_FALSE(r.empty());
    EXPECT_EQ(r.front(), 3);
    EXPECT_EQ(r.back(), 9993);
    for (std::size_t i = 0; i < r.size(); ++i)
        ASSERT_EQ(r[i], Tick(10 * i + 3)) << i;
}

TEST(RiseList, EraseFirstShiftsTheRest) {
    RiseList r;
    for (Tick t : {5, 15, 25, 35})
        r.push_back(t);
    r.eraseFirst();
    ASSERT_EQ(r.size(), 3u);
    EXPECT_EQ(r.front(), 15);
    EXPECT_EQ(r[1], 25);
    EXPECT_EQ(r.back(), 35);
}

TEST(RiseList, ClearKeepsNoRiseAndTheListTakesNewOnes) {
    RiseList r;
    for (Tick t = 0; t < 100; ++t)
        r.push_back(t);
    r.clear();
    EXPECT_TRUE(r.empty());
    r.push_back(42);
    EXPECT_EQ(r.size(), 1u);
    EXPECT_EQ(r.front(), 42);
    EXPECT_EQ(r.back(), 42);
}

TEST(RiseList, RisesWrittenIntoReservedRoomCountOnceTheSizeIsSet) {
    RiseList r;
    r.push_back(1);
    r.push_back(2);
    // As dataRun() does: room for a run's rises, written past size() from its locals.
    r.reserve(r.size() + 500);
    Tick* p = r.data();
    std::size_t n = r.size();
    for (Tick t = 3; t <= 502; ++t)
        p[n++] = t;
    EXPECT_EQ(r.size(), 2u);  // not counted until set
    r.setSize(n);
    ASSERT_EQ(r.size(), 502u);
    for (std::size_t i = 0; i < r.size(); ++i)
        ASSERT_EQ(r[i], Tick(i + 1)) << i;
    // Reserving no more than it has keeps the rises where they are.
    r.reserve(10);
    EXPECT_EQ(r.data(), p);
    EXPECT_EQ(r.back(), 502);
    // Growing past the room keeps them too.
    r.reserve(5000);
    ASSERT_EQ(r.size(), 502u);
    EXPECT_EQ(r.front(), 1);
    EXPECT_EQ(r.back(), 502);
    r.push_back(503);
    EXPECT_EQ(r.back(), 503);
}

}  // namespace
}  // namespace busdecode
