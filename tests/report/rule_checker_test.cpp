// Each rule against hand-made event streams: passes on clean traffic, fails on the
// right fault with the time of the first offending event.
#include <gtest/gtest.h>

#include "test_events.h"
#include "verify/rule_checker.h"
#include "verify/rules.h"

namespace busdecode {
namespace {

using test::bisscFrame;

std::vector<RuleOutcome> check(const std::string& rules_text, const std::vector<Event>& events) {
    const Rules rules = parseRules(rules_text, "r.toml", {});
    RuleChecker c(rules);
    const auto f = test::facts(100'000'000);
    c.begin(f);
    for (const auto& e : events)
        c.onEvent(e, f);
    c.end(f);
    return c.outcomes();
}

const RuleOutcome& find(const std::vector<RuleOutcome>& all, const std::string& name) {
    for (const auto& o : all)
        if (o.name() == name) return o;
    throw std::runtime_error("no outcome " + name);
}

std::vector<Event> cleanBiss(int n = 100) {
    std::vector<Event> v;
    for (int i = 0; i < n; ++i)
        v.push_back(bisscFrame(Tick(i) * 100000, 1000 + i));
    return v;
}

const char* kBissRules = R"(
[bissc]
max_crc_errors = 0
max_errors = 0
max_warnings = 2
clock_hz = [0.9e6, 1.1e6]
max_line_delay_ns = 500
max_proc_cycles = 4
min_frames = 100
timeout_us = [15, 25]
position = [0, 5000]
max_position_jump = 10
max_faults = 0
)";

TEST(RuleChecker, CleanTrafficPassesEveryRule) {
    const auto out = check(kBissRules, cleanBiss());
    ASSERT_EQ(out.size(), 11u);
    for (const auto& o : out)
        EXPECT_TRUE(o.passed) << o.name() << ": " << o.message;
    EXPECT_EQ(out[0].name(), "bissc.max_crc_errors");  // file order
    EXPECT_EQ(find(out, "bissc.min_frames").message, "100 frames (minimum 100)");
}

TEST(RuleChecker, CrcErrorFailsWithTheFirstTime) {
    auto ev = cleanBiss();
    ev[37] = bisscFrame(37 * 100000, 1037, false);
    ev[60] = bisscFrame(60 * 100000, 1060, false);
    const auto out = check(kBissRules, ev);
    const auto& o = find(out, "bissc.max_crc_errors");
    EXPECT_FALSE(o.passed);
    EXPECT_EQ(o.offending, 2u);
    ASSERT_TRUE(o.first_ns);
    EXPECT_DOUBLE_EQ(*o.first_ns, 3'700'000);
    EXPECT_EQ(o.message, "2 events with CRC errors (limit 0), first at 3.700 ms");
    EXPECT_FALSE(find(out, "bissc.max_faults").passed);
    EXPECT_TRUE(find(out, "bissc.max_errors").passed);
}

TEST(RuleChecker, FaultsAreCountedByKindMostFrequentFirst) {
    auto ev = cleanBiss();
    ev[37] = bisscFrame(37 * 100000, 1037, false);  // crc
    for (int i : {40, 41, 42})
        ev[i].error("short_frame");
    ev[42].error("glitch");  // one event, two kinds: counted once as a fault, once per kind
    const auto out = check(kBissRules, ev);
    const auto& o = find(out, "bissc.max_faults");
    EXPECT_FALSE(o.passed);
    EXPECT_EQ(o.offending, 4u);
    EXPECT_EQ(o.message,
              "4 events with errors (limit 0), first at 3.700 ms; by kind: short_frame 3, crc 1, "
              "glitch 1");
    // Kinds beyond the 64th are counted together.
    auto many = cleanBiss();
    for (int i = 0; i < 70; ++i)
        many[std::size_t(i)].error("kind" + std::to_string(100 + i));
    const auto many_out = check(kBissRules, many);
    const auto& m = find(many_out, "bissc.max_faults");
    EXPECT_NE(m.message.find("kind163 1, others 6"), std::string::npos) << m.message;
    // Clean traffic names no kinds.
    EXPECT_EQ(find(check(kBissRules, cleanBiss()), "bissc.max_faults").message,
              "0 events with errors (limit 0)");
}

TEST(RuleChecker, WarningLimitAboveZeroReportsWhereItWasPassed) {
    auto ev = cleanBiss();
    for (int i : {10, 20, 30})
        ev[i] = bisscFrame(Tick(i) * 100000, 1000 + i, true, 1, 0);
    const auto out = check(kBissRules, ev);
    const auto& o = find(out, "bissc.max_warnings");
    EXPECT_FALSE(o.passed);
    EXPECT_DOUBLE_EQ(*o.first_ns, 3'000'000);  // the third one went over the limit of 2
    EXPECT_NE(o.message.find("first at 1.000 ms, limit passed at 3.000 ms"), std::string::npos)
        << o.message;
}

TEST(RuleChecker, RangesAndMaximaOfFields) {
    auto ev = cleanBiss();
    ev[5] = bisscFrame(5 * 100000, 1005, true, 0, 1, 2e6, 900, 6, 30000);
    const auto out = check(kBissRules, ev);
    for (const char* name : {"bissc.max_errors", "bissc.clock_hz", "bissc.max_line_delay_ns",
                             "bissc.max_proc_cycles", "bissc.timeout_us"}) {
        const auto& o = find(out, name);
        EXPECT_FALSE(o.passed) << name;
        ASSERT_TRUE(o.first_ns) << name;
        EXPECT_DOUBLE_EQ(*o.first_ns, 500'000) << name;
    }
    EXPECT_NE(find(out, "bissc.clock_hz")
                  .message.find("1 of 100 values outside [900.000 kHz, 1.100 MHz]"),
              std::string::npos)
        << find(out, "bissc.clock_hz").message;
    EXPECT_NE(find(out, "bissc.max_line_delay_ns").message.find("(900 ns)"), std::string::npos)
        << find(out, "bissc.max_line_delay_ns").message;
}

TEST(RuleChecker, PositionRangeAndJump) {
    auto ev = cleanBiss();
    ev[50] = bisscFrame(50 * 100000, 9000);
    const auto out = check(kBissRules, ev);
    const auto& range = find(out, "bissc.position");
    EXPECT_FALSE(range.passed);
    EXPECT_DOUBLE_EQ(*range.first_ns, 5'000'000);
    const auto& jump = find(out, "bissc.max_position_jump");
    EXPECT_FALSE(jump.passed);
    EXPECT_EQ(jump.offending, 2u);  // out and back
    EXPECT_DOUBLE_EQ(*jump.first_ns, 5'000'000);
    EXPECT_NE(jump.message.find("1049 -> 9000"), std::string::npos) << jump.message;
}

TEST(RuleChecker, TooFewFramesFails) {
    const auto out = check(kBissRules, cleanBiss(40));
    const auto& o = find(out, "bissc.min_frames");
    EXPECT_FALSE(o.passed);
    EXPECT_EQ(o.message, "40 frames (minimum 100)");
    EXPECT_FALSE(o.first_ns);
}

TEST(RuleChecker, SsiRepeatMismatchAndMonoflopTime) {
    std::vector<Event> ev;
    for (int i = 0; i < 20; ++i)
        ev.push_back(test::ssiFrame(Tick(i) * 200000, 0x100 + i));
    ev[7] = test::ssiFrame(7 * 200000, 0x107, false);
    ev[12] = test::ssiFrame(12 * 200000, 0x10C, true, 40000);
    ev.push_back(bisscFrame(5'000'000, 1, false));  // another decoder's fault: not ssi's
    const auto out = check(
        "[ssi]\nmax_repeat_mismatches = 0\ntm_us = [15, 25]\nclock_hz = [50e3, 2e6]\nmin_frames = "
        "20\n",
        ev);
    const auto& rep = find(out, "ssi.max_repeat_mismatches");
    EXPECT_FALSE(rep.passed);
    EXPECT_DOUBLE_EQ(*rep.first_ns, 1'400'000);
    const auto& tm = find(out, "ssi.tm_us");
    EXPECT_FALSE(tm.passed);
    EXPECT_DOUBLE_EQ(*tm.first_ns, 2'400'000);
    EXPECT_TRUE(find(out, "ssi.clock_hz").passed);
    EXPECT_TRUE(find(out, "ssi.min_frames").passed);
}

TEST(RuleChecker, WholeNumbersInMessagesAreExact) {
    auto ev = cleanBiss();
    ev[3] = bisscFrame(3 * 100000, 1193046);
    const auto out = check("[bissc]\nposition = [0, 1193045]\n", ev);
    EXPECT_NE(out[0].message.find("outside [0, 1193045] (seen 1000 .. 1193046)"), std::string::npos)
        << out[0].message;
}

TEST(RuleChecker, CountOfAFieldTheDecoderNeverHasSaysNotChecked) {
    const auto out = check("[bissc]\nmax_repeat_mismatches = 0\nmax_errors = 0\n", cleanBiss());
    EXPECT_TRUE(out[0].passed);
    EXPECT_EQ(out[0].message, "not checked: no event carries repeat_match");
    EXPECT_EQ(out[1].message, "0 frames with nE active (limit 0)");
}

TEST(RuleChecker, NullFieldsAreSkippedAndAbsentFieldsSayNotChecked) {
    std::vector<Event> ev{test::ssiFrame(0, 1)};
    ev[0].set("tm_ns", Value(Null{}));  // the capture ended before data rose
    const auto out = check("[ssi]\ntm_us = [15, 25]\nmax_line_delay_ns = 10\n", ev);
    EXPECT_TRUE(out[0].passed);
    EXPECT_NE(out[0].message.find("not checked"), std::string::npos);
    EXPECT_NE(out[1].message.find("no event carries line_delay_ns"), std::string::npos);
}

TEST(RuleChecker, ExpectedRegisterValues) {
    std::vector<Event> ev = cleanBiss(3);
    ev.push_back(test::bisscRegister(1'000'000, 0x7E, 0x69));
    ev.push_back(test::bisscRegister(2'000'000, 0x7F, 0x42));
    const auto out = check("[bissc]\nregisters = { 0x7E = 0x69, 0x7F = 0x43, 0x10 = 1 }\n", ev);
    ASSERT_EQ(out.size(), 3u);
    EXPECT_TRUE(find(out, "bissc.registers.0x7E").passed);
    const auto& bad = find(out, "bissc.registers.0x7F");
    EXPECT_FALSE(bad.passed);
    EXPECT_DOUBLE_EQ(*bad.first_ns, 2'000'000);
    EXPECT_NE(bad.message.find("(0x42)"), std::string::npos) << bad.message;
    EXPECT_NE(find(out, "bissc.registers.0x10").message.find("never accessed"), std::string::npos);
}

TEST(RuleChecker, EventSummaryCountsPrimaryEvents) {
    const Rules rules =
        parseRules("[bissc]\nmin_frames = 1\n[ssi]\nmin_frames = 1\n", "r.toml", {});
    RuleChecker c(rules);
    const auto f = test::facts(1);
    c.begin(f);
    c.onEvent(bisscFrame(0, 1), f);
    c.onEvent(test::bisscRegister(10, 1, 1), f);
    c.end(f);
    EXPECT_EQ(c.eventSummary(), "bissc 1 frame, ssi 0 frames");
}

}  // namespace
}  // namespace busdecode
