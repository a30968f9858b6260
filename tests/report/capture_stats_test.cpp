// CaptureStats from hand-made events: counts, errors by kind, flags, timing sketches,
// position range and jump, registers, faults, bounded memory.
#include <gtest/gtest.h>

#include "report/capture_stats.h"
#include "test_events.h"

namespace busdecode {
namespace {

using test::bisscFrame;

TEST(CaptureStats, CountsErrorsFlagsAndTimingPerGroup) {
    CaptureStats s;
    s.begin(test::facts(10'000'000));
    for (int i = 0; i < 100; ++i) {
        const bool bad_crc = i == 40 || i == 70;
        s.add(bisscFrame(Tick(i) * 100000, 1000 + i, !bad_crc, i == 50 ? 0 : 1, 1, 1e6, 100 + i));
    }
    s.add(test::bisscRegister(5'000'000, 0x78, 0x4D));
    s.end(test::facts(10'000'000));

    ASSERT_EQ(s.instances(), std::vector<std::string>{"bissc"});
    const auto groups = s.groupsOf("bissc");
    ASSERT_EQ(groups.size(), 2u);
    const GroupStats& f = *groups[0];
    EXPECT_EQ(f.type, "frame");
    EXPECT_EQ(f.count, 100u);
    EXPECT_EQ(f.faulty, 2u);
    EXPECT_EQ(f.errors.at("crc"), 2u);
    bool saw_crc_flag = false, saw_ne = false;
    for (const auto& [k, c] : f.flags) {
        if (k == "crc_ok") {
            saw_crc_flag = true;
            EXPECT_EQ(c.false_count, 2u);
            EXPECT_EQ(c.true_count, 98u);
        }
        if (k == "nE") {
            saw_ne = true;
            EXPECT_EQ(c.false_count, 1u);  // active
        }
    }
    EXPECT_TRUE(saw_crc_flag);
    EXPECT_TRUE(saw_ne);
    const QuantileSketch* delay = nullptr;
    for (const auto& [k, sk] : f.timing)
        if (k == "line_delay_ns") delay = &sk;
    ASSERT_NE(delay, nullptr);
    EXPECT_DOUBLE_EQ(delay->min(), 100);
    EXPECT_DOUBLE_EQ(delay->max(), 199);
    EXPECT_NEAR(delay->median(), 149, 1.5);
    // Frames start every 100 us and last 60 us: 40 us pauses.
    EXPECT_EQ(f.pause_ns.count(), 99u);
    EXPECT_NEAR(f.pause_ns.median(), 40000, 200);

    const auto* regs = s.registers("bissc");
    ASSERT_NE(regs, nullptr);
    EXPECT_EQ(regs->at(0x78).reads, 1u);
    EXPECT_EQ(regs->at(0x78).last_data, 0x4D);

    ASSERT_EQ(s.firstFaults().size(), 2u);
    EXPECT_EQ(s.firstFaults()[0].start, 40 * 100000);
    ASSERT_TRUE(s.firstFaultyEvent().has_value());
    EXPECT_EQ(s.firstFaultyEvent()->start, 40 * 100000);
}

TEST(CaptureStats, PositionRangeAndLargestJump) {
    CaptureStats s;
    s.begin(test::facts(1'000'000'000));
    std::int64_t pos = 500;
    for (int i = 0; i < 1000; ++i) {
        pos += (i == 600) ? 7000 : 3;  // one big jump at frame 600
        s.add(bisscFrame(Tick(i) * 100000, pos));
    }
    const auto* p = s.position("bissc");
    ASSERT_NE(p, nullptr);
    EXPECT_EQ(p->count, 1000u);
    EXPECT_DOUBLE_EQ(p->min, 503);
    EXPECT_DOUBLE_EQ(p->max, 500 + 999 * 3 + 7000);
    EXPECT_DOUBLE_EQ(p->max_jump, 7000);
    EXPECT_EQ(p->max_jump_at, 600 * 100000);
}

TEST(CaptureStats, TmcGrayRepliesAreNotPositions) {
    // The TMC8100 answers read_encoder with the word as received (Gray) and then converted
    // to binary; only the binary one is a position.
    CaptureStats s;
    s.begin(test::facts(1'000'000'000));
    auto reply = [](Tick t, const char* meaning, std::int64_t position) {
        Event e;
        e.proto = e.instance = "tmc8100";
        e.type = "reply";
        e.start = t;
        e.end = t + 1000;
        e.set("meaning", std::string(meaning)).set("position", position);
        return e;
    };
    for (int i = 0; i < 6; ++i) {
        const std::int64_t binary = 0x8000 + i;
        s.add(reply(Tick(i) * 100000, "raw_position", binary ^ (binary >> 1)));
        s.add(reply(Tick(i) * 100000 + 50000, "binary_position", binary));
    }
    const auto* p = s.position("tmc8100");
    ASSERT_NE(p, nullptr);
    EXPECT_EQ(p->count, 6u);
    EXPECT_DOUBLE_EQ(p->min, 0x8000);
    EXPECT_DOUBLE_EQ(p->max, 0x8005);
    EXPECT_DOUBLE_EQ(p->max_jump, 1);
}

TEST(CaptureStats, MemoryStaysBoundedOnLongCaptures) {
    CaptureStats s;
    s.begin(test::facts(0));
    for (int i = 0; i < 200000; ++i)
        s.add(bisscFrame(Tick(i) * 50000, i % 5000, i % 1000 != 7));
    const auto* p = s.position("bissc");
    ASSERT_NE(p, nullptr);
    EXPECT_LE(p->trace.points().size(), PositionTrace::kMaxPoints);
    EXPECT_GE(p->trace.points().size(), PositionTrace::kMaxPoints / 2);
    std::uint64_t n = 0;
    for (const auto& pt : p->trace.points())
        n += pt.n;
    EXPECT_EQ(n, 200000u);  // every frame is in some point
    EXPECT_EQ(s.firstFaults().size(), CaptureStats::kMaxFaults);
    EXPECT_EQ(s.totalFaults(), 200u);
    // Spikes survive decimation: the trace still spans the full range.
    double lo = 1e9, hi = -1e9;
    for (const auto& pt : p->trace.points()) {
        lo = std::min(lo, pt.lo);
        hi = std::max(hi, pt.hi);
    }
    EXPECT_EQ(lo, 0);
    EXPECT_EQ(hi, 4999);
}

TEST(CaptureStats, OverlappingEventsHaveNoPauseBetweenThem) {
    // Two register accesses carried by the same control frames span the same 2 ms; the
    // third starts 1 ms after they end.
    CaptureStats s;
    s.begin(test::facts(10'000'000));
    s.add(test::bisscRegister(0, 0x48, 0xA5));
    s.add(test::bisscRegister(100'000, 0x49, 0x5A));  // ends at 2.1 ms
    s.add(test::bisscRegister(3'100'000, 0x7E, 0x12));
    const auto& g = *s.groupsOf("bissc")[0];
    EXPECT_EQ(g.count, 3u);
    ASSERT_EQ(g.pause_ns.count(), 1u);
    EXPECT_DOUBLE_EQ(g.pause_ns.min(), 1'000'000);
}

TEST(CaptureStats, PausesAreMeasuredOnEachLineApart) {
    // rx and tx bytes of 10 us interleave: each line pauses 40 us between its bytes,
    // though the other line's byte sits in between.
    CaptureStats s;
    s.begin(test::facts(1'000'000'000));
    for (int i = 0; i < 10; ++i)
        for (const char* line : {"rx", "tx"}) {
            Event e;
            e.proto = e.instance = "uart";
            e.type = "byte";
            e.start = Tick(i) * 50'000 + (line[0] == 't' ? 20'000 : 0);
            e.end = e.start + 10'000;
            e.set("line", std::string(line)).set("value", std::int64_t(0x41));
            s.add(e);
        }
    const auto& g = *s.groupsOf("uart")[0];
    EXPECT_EQ(g.count, 20u);
    EXPECT_EQ(g.pause_ns.count(), 18u);  // 9 on each line
    EXPECT_DOUBLE_EQ(g.pause_ns.min(), 40'000);
    EXPECT_DOUBLE_EQ(g.pause_ns.max(), 40'000);
}

TEST(CaptureStats, MomentsAreNotTimingFields) {
    EXPECT_TRUE(isTimingField("rtt_ns"));
    EXPECT_TRUE(isTimingField("line_delay_ns"));
    EXPECT_TRUE(isTimingField("clock_hz"));
    EXPECT_FALSE(isTimingField("request_start_ns"));  // when, not how long
    EXPECT_FALSE(isTimingField("end_ns"));
    EXPECT_FALSE(isTimingField("position"));
}

TEST(CaptureStats, SeveralBusesKeepSeparateGroups) {
    CaptureStats s;
    auto f = test::facts(10'000'000);
    f.protos = {"bissc", "ssi"};
    s.begin(f);
    s.add(bisscFrame(0, 10));
    s.add(test::ssiFrame(100, 0x1234, false));
    s.add(bisscFrame(200000, 11));
    EXPECT_EQ(s.instances(), (std::vector<std::string>{"bissc", "ssi"}));
    EXPECT_EQ(s.groupsOf("bissc")[0]->count, 2u);
    EXPECT_EQ(s.groupsOf("ssi")[0]->errors.at("repeat_mismatch"), 1u);
}

}  // namespace
}  // namespace busdecode
