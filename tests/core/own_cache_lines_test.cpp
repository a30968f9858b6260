// OwnLinesArray: the reading thread's per-edge levels, in whole cache lines of their own.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "core/own_cache_lines.h"

using namespace busdecode;

namespace {

std::uintptr_t address(const void* p) {
    return reinterpret_cast<std::uintptr_t>(p);
}

}  // namespace

TEST(OwnLinesArray, StartsOnALineAndHoldsItsValues) {
    for (std::size_t n : {1u, 3u, 127u, 128u, 129u, 1000u}) {
        OwnLinesArray<std::uint8_t> a;
        a.assign(n, 1);
        EXPECT_EQ(address(a.data()) % kOwnLineBytes, 0u) << n;
        ASSERT_EQ(a.size(), n);
        EXPECT_EQ(a.toVector(), std::vector<std::uint8_t>(n, 1));
        a[n - 1] = 0;
        EXPECT_EQ(a.toVector().back(), 0);
        EXPECT_EQ(a.toVector().front(), n == 1 ? 0 : 1);
    }
}

TEST(OwnLinesArray, OwnsTheWholeOfItsLastLine) {
    // Nothing else may be put in the rest of its last line: the storage is whole lines.
    // (glibc happens to leave that rest unused after an aligned allocation, so where
    // later allocations land would not show it.)
    for (std::size_t n : {1u, 5u, 64u, 127u, 128u, 129u, 200u}) {
        OwnLinesArray<std::uint16_t> a;
        a.assign(n, 0);
        EXPECT_EQ(a.ownedBytes() % kOwnLineBytes, 0u) << n;
        EXPECT_GE(a.ownedBytes(), n * sizeof(std::uint16_t)) << n;
        EXPECT_LT(a.ownedBytes(), n * sizeof(std::uint16_t) + kOwnLineBytes) << n;
    }
}

TEST(OwnLinesArray, AssignAgainStartsAfresh) {
    OwnLinesArray<std::int32_t> a;
    a.assign(4, 7);
    a.assign(2, -1);
    EXPECT_EQ(a.toVector(), (std::vector<std::int32_t>{-1, -1}));
    a.assign(0, 5);
    EXPECT_EQ(a.size(), 0u);
    EXPECT_TRUE(a.toVector().empty());
}
