// The columns read() builds (python/src/event_columns.h): each kind of value, the
// promotions between them, and what a column becomes when its values do not agree.
#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <limits>

#include "event_columns.h"

namespace busdecode::py {
namespace {

template <class T>
std::vector<T> values(const LaneBuffer<T>& b) {
    return {b.begin(), b.end()};
}

Column columnOf(std::initializer_list<Value> values) {
    Column c;
    for (const auto& v : values)
        c.append(v);
    return c;
}

TEST(EventColumns, IntegersStayIntegersWithNullsMasked) {
    Column c = columnOf({std::int64_t(-3), Null{}, std::uint64_t(7)});
    EXPECT_EQ(c.kind, Column::Kind::Int);
    EXPECT_EQ(values(c.lanes), (std::vector<std::uint64_t>{std::uint64_t(-3), 0, 7}));
    EXPECT_EQ(values(c.nulls), (std::vector<std::uint8_t>{0, 1, 0}));
}

TEST(EventColumns, AnIntegerBeyondInt64MakesAnUnsignedColumn) {
    const std::uint64_t big = std::numeric_limits<std::uint64_t>::max();
    Column c = columnOf({std::int64_t(1), big});
    EXPECT_EQ(c.kind, Column::Kind::UInt);
    EXPECT_EQ(c.lanes.back(), big);
    // ... unless a negative number came before: then no 64-bit kind holds both.
    Column mixed = columnOf({std::int64_t(-1), big});
    ASSERT_EQ(mixed.kind, Column::Kind::Object);
    EXPECT_EQ(mixed.objects[0], Value(std::int64_t(-1)));
    EXPECT_EQ(mixed.objects[1], Value(big));
}

TEST(EventColumns, ADoubleTurnsIntegersIntoReals) {
    Column c = columnOf({std::int64_t(2), Null{}, 2.5});
    ASSERT_EQ(c.kind, Column::Kind::Real);
    EXPECT_EQ(std::bit_cast<double>(c.lanes[0]), 2.0);
    EXPECT_EQ(std::bit_cast<double>(c.lanes[2]), 2.5);
    EXPECT_EQ(c.nulls[1], 1);
    c.append(std::int64_t(4));
    EXPECT_EQ(std::bit_cast<double>(c.lanes[3]), 4.0);
    c.append(-0.5);  // a double into a column of doubles
    EXPECT_EQ(std::bit_cast<double>(c.lanes[4]), -0.5);
    EXPECT_EQ(c.nulls[4], 0);
    EXPECT_EQ(c.kind, Column::Kind::Real);
}

TEST(EventColumns, StringsAreCodesIntoTheDistinctOnes) {
    Column c = columnOf({std::string("rx"), std::string("tx"), Null{}, std::string("rx")});
    ASSERT_EQ(c.kind, Column::Kind::Text);
    EXPECT_EQ(c.texts, (std::vector<std::string>{"rx", "tx"}));
    EXPECT_EQ(c.lanes[3], 0u);
    EXPECT_EQ(c.nulls[2], 1);
}

TEST(EventColumns, KindsThatDoNotMixMakeAColumnOfValues) {
    Column c = columnOf({true, std::int64_t(1), std::string("x"), Null{}});
    ASSERT_EQ(c.kind, Column::Kind::Object);
    EXPECT_EQ(c.objects,
              (std::vector<Value>{true, std::int64_t(1), std::string("x"), Value(Null{})}));
    Column t = columnOf({std::string("a"), 1.5});
    ASSERT_EQ(t.kind, Column::Kind::Object);
    EXPECT_EQ(t.objects, (std::vector<Value>{std::string("a"), 1.5}));
}

TEST(EventColumns, TablesPadMissingFieldsAndKeepTheLastOfARepeatedKey) {
    Table t;
    Event a;
    a.add("x", std::int64_t(1)).add("y", std::int64_t(2)).add("x", std::int64_t(3));
    a.error("crc");
    Event b;
    b.add("z", true).add("proto", std::string("ignored"));
    t.add(a, 10, 20);
    t.add(b, 30, 40);
    ASSERT_EQ(t.columns.size(), 3u);  // x, y, z: the common keys are never columns
    EXPECT_EQ(values(t.columns[0].lanes), (std::vector<std::uint64_t>{3, 0}));
    EXPECT_EQ(values(t.columns[0].nulls), (std::vector<std::uint8_t>{0, 1}));
    EXPECT_EQ(values(t.columns[2].nulls), (std::vector<std::uint8_t>{1, 0}));
    EXPECT_EQ(values(t.start_ns), (std::vector<std::int64_t>{10, 30}));
    EXPECT_EQ(values(t.errors), (std::vector<std::uint32_t>{1, 0}));
    EXPECT_EQ(t.error_sets[1], (std::vector<std::string>{"crc"}));
}

TEST(LaneBuffer, KeepsItsValuesThroughGrowthMovesAndPops) {
    LaneBuffer<std::uint64_t> b;
    EXPECT_TRUE(b.empty());
    const std::uint64_t n = 3'000'000;  // 24 MB: several remaps, past the huge-page size
    for (std::uint64_t i = 0; i < n; ++i)
        b.push_back(i * 7);
    b.pop_back();
    LaneBuffer<std::uint64_t> moved(std::move(b));
    EXPECT_TRUE(b.empty());
    ASSERT_EQ(moved.size(), n - 1);
    EXPECT_EQ(moved.back(), (n - 2) * 7);
    for (std::uint64_t i = 0; i < n - 1; i += 99'991)
        ASSERT_EQ(moved[i], i * 7) << i;
    b = std::move(moved);
    EXPECT_EQ(b.size(), n - 1);
    b.push_back(1);
    EXPECT_EQ(b.back(), 1u);
}

}  // namespace
}  // namespace busdecode::py
