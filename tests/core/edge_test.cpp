// Edge packs a time, a line and a level into one 8-byte word (core/edge.h): every field
// must read back as written, at the ends of its range, and writing one field must leave
// the others alone.
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/edge.h"
#include "core/waveform.h"

namespace busdecode {
namespace {

TEST(Edge, FieldsReadBackAsWrittenAtTheEndsOfTheirRanges) {
    static_assert(sizeof(Edge) == 8);
    const std::vector<Tick> times = {0,
                                     1,
                                     -1,
                                     1'000'000'007,
                                     -123'456'789'012,
                                     kMaxEdgeTick,
                                     kMinEdgeTick,
                                     kMaxEdgeTick - 1,
                                     kMinEdgeTick + 1,
                                     Tick(1) << 54,
                                     -(Tick(1) << 54)};
    for (const Tick t : times)
        for (std::uint32_t line = 0; line < kMaxSelectedLines; ++line)
            for (std::uint8_t level = 0; level < 2; ++level) {
                const Edge e(t, line, level);
                ASSERT_EQ(e.t, t) << line << " " << int(level);
                ASSERT_EQ(e.line, line) << t;
                ASSERT_EQ(e.level, level) << t << " " << line;
            }
}

TEST(Edge, LineAndLevelIsTheLineTwiceAndTheLevel) {
    // BiSS-C's runs dispatch on it (BisscDecoder::takeDataEdge()): role * 2 + level.
    for (const Tick t : {Tick(0), Tick(-1), kMaxEdgeTick, kMinEdgeTick, Tick(0xff)})
        for (std::uint32_t line = 0; line < kMaxSelectedLines; ++line)
            for (std::uint8_t level = 0; level < 2; ++level)
                ASSERT_EQ(Edge(t, line, level).lineAndLevel(), line * 2 + level) << t;
    Edge e(12345, 3, 0);
    e.level = 1;  // written through the fields, read as the word
    EXPECT_EQ(e.lineAndLevel(), 7u);
}

TEST(Edge, WritingOneFieldLeavesTheOthers) {
    Edge e(kMaxEdgeTick - 40, 127, 1);
    e.t += 40;  // as tests shift edges in time
    EXPECT_EQ(e.t, kMaxEdgeTick);
    EXPECT_EQ(e.line, 127u);
    EXPECT_EQ(e.level, 1u);
    e.line = 5;
    e.level = 0;
    EXPECT_EQ(e.t, kMaxEdgeTick);
    EXPECT_EQ(e.line, 5u);
    e.t = kMinEdgeTick;
    EXPECT_EQ(e.line, 5u);
    EXPECT_EQ(e.level, 0u);
    EXPECT_EQ(e.t, kMinEdgeTick);
}

TEST(Edge, TimesFitWithin2To55Ticks) {
    EXPECT_TRUE(edgeTickFits(kMaxEdgeTick));
    EXPECT_TRUE(edgeTickFits(kMinEdgeTick));
    EXPECT_FALSE(edgeTickFits(kMaxEdgeTick + 1));
    EXPECT_FALSE(edgeTickFits(kMinEdgeTick - 1));
    EXPECT_EQ(kMaxEdgeTick, 36028797018963967);
}

// Generated captures obey the same limits: more lines than an Edge names, or a time it
// cannot hold, is a generator's mistake, caught where the waveform is built.
TEST(Edge, WaveformsKeepToWhatAnEdgeHolds) {
    const Timebase ns{1, 1'000'000'000};
    EXPECT_THROW(WaveBuilder(ns, std::vector<std::string>(kMaxSelectedLines + 1, "x"), {}),
                 std::length_error);
    WaveBuilder b(ns, std::vector<std::string>(kMaxSelectedLines, "x"), {});
    b.set(127, kMaxEdgeTick, false);
    EXPECT_THROW(b.set(127, kMaxEdgeTick + 1, true), std::out_of_range);
    const Waveform w = b.build(kMaxEdgeTick);
    ASSERT_EQ(w.edges.size(), 1u);
    EXPECT_EQ(w.edges[0].t, kMaxEdgeTick);
    EXPECT_EQ(w.edges[0].line, 127u);
    EXPECT_THROW(mergeWaveforms(w, w), std::length_error);
}

}  // namespace
}  // namespace busdecode
