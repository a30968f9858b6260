// Faults the TMC8100 layer must report, each on a generated capture with every event
// compared exactly: a firmware that reports the wrong binary, an answer that differs
// from the encoder cable, GPIO6 contradicting the traffic, commands sent before the
// replies were read, replies nobody asked for or out of order, BiSS demo replies.
#include <gtest/gtest.h>

#include "core/gray.h"
#include "core/registry.h"
#include "core/session.h"
#include "scenario_expect.h"

using namespace busdecode;
using namespace busdecode::test;

namespace {

std::vector<Event> decode(const Tmc8100Scenario& sc, bool with_ssi = false,
                          std::map<std::string, std::string> opts = {}) {
    registerDecoders();
    std::vector<DecoderRequest> req = {DecoderRequest{"tmc8100", {}, std::move(opts)}};
    if (with_ssi) req.push_back(DecoderRequest{"ssi", {}, {}});
    return decodeWaveform(sc.build(), req);
}

// Expected events of one ordinary 0x80 read whose command is transfer c.
void appendRead(std::vector<Expected>& want, const ScenarioExpect& x, std::size_t c,
                std::int64_t gray, std::int64_t binary, std::int64_t flags, bool consistent,
                std::vector<std::pair<std::string, Value>> read_extra = {},
                std::vector<std::string> read_errors = {},
                std::vector<std::string> first_reply_errors = {}) {
    want.push_back(x.command(c, 0x80, "read_encoder"));
    want.push_back(x.read(c, c + 3, gray, binary, flags, consistent, read_extra, read_errors));
    want.push_back(x.reply(c + 1, "raw_position", S("read_encoder"), {{"position", I(gray)}},
                           first_reply_errors));
    want.push_back(x.command(c + 1, 0x00, "dummy"));
    want.push_back(x.reply(c + 2, "binary_position", S("read_encoder"), {{"position", I(binary)}}));
    want.push_back(x.command(c + 2, 0x00, "dummy"));
    want.push_back(x.reply(c + 3, "flags", S("read_encoder"), {{"flags", I(flags)}}));
    want.push_back(x.command(c + 3, 0x00, "dummy"));
}

}  // namespace

TEST(Tmc8100Faults, FirmwareFaultBinaryIsNotTheGrayDecode) {
    Tmc8100Scenario sc;
    Tmc8100Scenario::EncoderRead r;
    r.ssi_word = Tmc8100Scenario::ssiWord(0, 0, 0x1234);
    r.reported_binary = 0x1334;  // one bit off
    sc.readEncoder(r);
    auto events = decode(sc);
    ScenarioExpect x{sc};
    std::vector<Expected> want;
    appendRead(want, x, 0, 0x1B2E, 0x1334, 0, false, {}, {"inconsistent"});
    expectEvents(events, "tmc8100", want);
}

#ifdef BUSDECODE_HAVE_SSI
TEST(Tmc8100Faults, EncoderSideMismatchIsCaughtBySsiInTheSamePass) {
    Tmc8100Scenario sc;
    Tmc8100Scenario::EncoderRead good, bad;
    good.ssi_word = Tmc8100Scenario::ssiWord(0, 1, 0x0F00);
    bad.ssi_word = Tmc8100Scenario::ssiWord(0, 1, 0x0F01);
    bad.reported_raw = std::uint16_t(binaryToGray(0x0F00));  // TMC8100 answers the old position
    sc.readEncoder(good);
    sc.pause(25000);
    sc.readEncoder(bad);
    auto events = decode(sc, true);
    ScenarioExpect x{sc};
    const std::int64_t g0 = binaryToGray(0x0F00), g1 = binaryToGray(0x0F01);
    std::vector<Expected> want;
    appendRead(want, x, 0, g0, 0x0F00, 0, true,
               {{"ssi_match", Value(true)}, {"encoder_st", I(g0)}});
    appendRead(want, x, 4, g0, 0x0F00, 0, true,
               {{"ssi_match", Value(false)}, {"encoder_st", I(g1)}}, {"ssi_mismatch"});
    expectEvents(events, "tmc8100", want);
    EXPECT_EQ(only(events, "ssi", "frame").size(), 2u);
}

TEST(Tmc8100Faults, NoEncoderFrameWhileSsiRuns) {
    // The second read's encoder clock never runs (say the cable is off): the SSI
    // decoder sees frames elsewhere in the capture but none for this read.
    Tmc8100Scenario sc;
    Tmc8100Scenario::EncoderRead r;
    r.ssi_word = Tmc8100Scenario::ssiWord(0, 0, 0x0042);
    sc.readEncoder(r);
    sc.pause(25000);
    sc.transfer(0x80000000u, 0);
    sc.pause(30000);
    sc.setAvail(true);
    sc.pause(2000);
    sc.transfer(0, 0x1000FFFFu);
    sc.transfer(0, 0x2000AAAAu);
    sc.transfer(0, 0x70000000u);
    auto events = decode(sc, true);
    auto reads = only(events, "tmc8100", "encoder_read");
    ASSERT_EQ(reads.size(), 2u);
    EXPECT_EQ(show(*reads[0].get("ssi_match")), "true");
    EXPECT_EQ(show(*reads[1].get("ssi_match")), "false");
    EXPECT_EQ(reads[1].errors, (std::vector<std::string>{"no_encoder_frame"}));
}
#endif

TEST(Tmc8100Faults, WithoutAnEncoderDecoderThereIsNoSsiMatchField) {
    Tmc8100Scenario sc;
    Tmc8100Scenario::EncoderRead r;
    r.ssi_word = Tmc8100Scenario::ssiWord(0, 0, 0x0042);
    sc.readEncoder(r);
    auto reads = only(decode(sc), "tmc8100", "encoder_read");
    ASSERT_EQ(reads.size(), 1u);
    EXPECT_FALSE(reads[0].has("ssi_match"));
    EXPECT_TRUE(reads[0].errors.empty());
}

TEST(Tmc8100Faults, HostReadsBeforeGpio6) {
    Tmc8100Scenario sc;
    Tmc8100Scenario::EncoderRead r;
    r.ssi_word = Tmc8100Scenario::ssiWord(0, 0, 0x0100);
    r.host_waits = false;  // GPIO6 rises only while the first read is already running
    sc.readEncoder(r);
    auto events = decode(sc);
    ScenarioExpect x{sc};
    std::vector<Expected> want;
    appendRead(want, x, 0, 0x0180, 0x0100, 0, true, {}, {}, {"avail_low"});
    expectEvents(events, "tmc8100", want);
}

TEST(Tmc8100Faults, Gpio6NeverRises) {
    Tmc8100Scenario sc;
    Tmc8100Scenario::EncoderRead r;
    r.ssi_word = Tmc8100Scenario::ssiWord(0, 0, 0x0100);
    r.avail_rises = false;
    sc.readEncoder(r);
    auto events = decode(sc);
    ScenarioExpect x{sc};
    std::vector<Expected> want;
    appendRead(want, x, 0, 0x0180, 0x0100, 0, true, {}, {}, {"avail_low"});
    expectEvents(events, "tmc8100", want);
}

TEST(Tmc8100Faults, Gpio6RisesWithNoCommandWaiting) {
    Tmc8100Scenario sc;
    sc.getVersion(1, 0);
    sc.pause(5000);
    const double rise = sc.now();
    sc.setAvail(true);
    sc.pause(3000);
    sc.setAvail(false);
    auto events = decode(sc);
    ScenarioExpect x{sc};
    const Tick t = Tick(rise);
    expectEvents(events, "tmc8100",
                 {x.command(0, 0xFF, "get_version"),
                  x.reply(1, "version", S("get_version"), {{"major", I(1)}, {"minor", I(0)}}),
                  x.command(1, 0x00, "dummy"),
                  Expected{"avail", t, t, {{"level", I(1)}}, {"unexpected_avail"}}});
}

TEST(Tmc8100Faults, CommandSentBeforeRepliesWereRead) {
    // After one of three replies the host asks for the version; a FIFO firmware still
    // hands out the two remaining encoder words first, then the version.
    Tmc8100Scenario sc;
    sc.transfer(0x80000000u, 0);
    sc.ssiFrame(Tmc8100Scenario::ssiWord(0, 0, 0x0001));
    sc.pause(1500);
    sc.setAvail(true);
    sc.pause(3000);
    sc.transfer(0, 0x10000001u);
    sc.transfer(0xFF000000u, 0x20000001u);
    sc.transfer(0, 0x70000000u);
    sc.transfer(0, 0xFF000100u);
    auto events = decode(sc);
    ScenarioExpect x{sc};
    expectEvents(
        events, "tmc8100",
        {x.command(0, 0x80, "read_encoder"), x.read(0, 3, 1, 1, 0, true),
         x.reply(1, "raw_position", S("read_encoder"), {{"position", I(1)}}),
         x.command(1, 0, "dummy"),
         x.reply(2, "binary_position", S("read_encoder"), {{"position", I(1)}}),
         x.command(2, 0xFF, "get_version", {"replies_pending"}),
         x.reply(3, "flags", S("read_encoder"), {{"flags", I(0)}}), x.command(3, 0, "dummy"),
         x.reply(4, "version", S("get_version"), {{"major", I(1)}, {"minor", I(0)}}),
         x.command(4, 0, "dummy")});
}

TEST(Tmc8100Faults, LastReadMayCarryTheNextCommand) {
    Tmc8100Scenario sc;
    Tmc8100Scenario::EncoderRead r;
    r.ssi_word = Tmc8100Scenario::ssiWord(0, 0, 7);
    r.next_command = 0xFF000000u;
    sc.readEncoder(r);
    sc.pause(1000);
    sc.setAvail(true);
    sc.pause(1000);
    sc.transfer(0, 0xFF000102u);
    auto events = decode(sc);
    ScenarioExpect x{sc};
    const std::int64_t g = binaryToGray(7);
    expectEvents(
        events, "tmc8100",
        {x.command(0, 0x80, "read_encoder"), x.read(0, 3, g, 7, 0, true),
         x.reply(1, "raw_position", S("read_encoder"), {{"position", I(g)}}),
         x.command(1, 0, "dummy"),
         x.reply(2, "binary_position", S("read_encoder"), {{"position", I(7)}}),
         x.command(2, 0, "dummy"), x.reply(3, "flags", S("read_encoder"), {{"flags", I(0)}}),
         x.command(3, 0xFF, "get_version"),
         x.reply(4, "version", S("get_version"), {{"major", I(1)}, {"minor", I(2)}}),
         x.command(4, 0, "dummy")});
}

TEST(Tmc8100Faults, UnsolicitedAndMissingReplies) {
    Tmc8100Scenario sc;
    sc.getProtocol("SSI ");       // identifies the application firmware
    sc.transfer(0, 0x10001234u);  // 2: data with no command waiting
    sc.transfer(0x80000000u, 0);  // 3
    sc.ssiFrame(Tmc8100Scenario::ssiWord(0, 0, 3));
    sc.pause(1500);
    sc.setAvail(true);
    sc.pause(3000);
    sc.transfer(0, 0x10000002u);  // 4
    sc.transfer(0, 0x70000000u);  // 5: the 0x20 word went missing
    auto events = decode(sc);
    ScenarioExpect x{sc};
    Expected read{
        "encoder_read",
        x.start(3),
        x.end(5),
        {{"gray", I(2)}, {"binary", Value(Null{})}, {"flags", I(0)}, {"consistent", Value(Null{})}},
        {"incomplete"}};
    expectEvents(
        events, "tmc8100",
        {x.command(0, 0xFE, "get_protocol"),
         x.reply(1, "protocol", S("get_protocol"), {{"text", S("SSI ")}}), x.command(1, 0, "dummy"),
         x.reply(2, "raw_position", Value(Null{}), {}, {"unsolicited_reply"}),
         x.command(2, 0, "dummy"), x.command(3, 0x80, "read_encoder"), read,
         x.reply(4, "raw_position", S("read_encoder")), x.command(4, 0, "dummy"),
         x.reply(5, "flags", S("read_encoder"), {{"flags", I(0)}}, {"unexpected_reply"}),
         x.command(5, 0, "dummy")});
}

TEST(Tmc8100Faults, BissDemoRepliesWithClockEdgesAndCrc) {
    // BiSS demo: 13-bit ST, [0x70, nE:nW, CRC received, CRC calculated ^ 0x3F], [0x71 .. edges].
    for (bool announce : {true, false}) {
        SCOPED_TRACE(announce ? "protocol announced" : "protocol detected from 0x71");
        Tmc8100Scenario sc;
        std::size_t c = 0;
        if (announce) {
            sc.getProtocol("BISS");
            c = 2;
        }
        for (std::uint32_t crc_calc : {0x2Bu, 0x2Cu}) {
            sc.transfer(0x80000000u, 0);
            sc.pause(30000);
            sc.setAvail(true);
            sc.pause(3000);
            sc.transfer(0, 0x10000A5Au);
            sc.transfer(0, 0x20000A5Au ^ 0);  // binary as reported (not Gray-checked here)
            sc.transfer(0, 0x70022B00u | crc_calc);
            sc.transfer(0, 0x71000034u);
            sc.pause(1000);
            sc.setAvail(false);
        }
        auto reads = only(decode(sc), "tmc8100", "encoder_read");
        ASSERT_EQ(reads.size(), 2u);
        ScenarioExpect x{sc};
        for (int k = 0; k < 2; ++k) {
            SCOPED_TRACE(k);
            const Event& e = reads[k];
            EXPECT_EQ(e.start, x.start(c + 5 * k));
            EXPECT_EQ(e.end, x.end(c + 5 * k + 4));
            EXPECT_EQ(show(*e.get("gray")), "2650");
            EXPECT_EQ(show(*e.get("flags")), "2");
            EXPECT_EQ(show(*e.get("nE")), "1");
            EXPECT_EQ(show(*e.get("nW")), "0");
            EXPECT_EQ(show(*e.get("crc_rx")), "43");
            EXPECT_EQ(show(*e.get("crc_ok")), k == 0 ? "true" : "false");
            EXPECT_EQ(show(*e.get("clock_edges")), "52");
            // 0xA5A is not the Gray decode of itself: the demo frame here is binary.
            std::vector<std::string> errs = {"inconsistent"};
            if (k == 1) errs.insert(errs.begin(), "crc");
            EXPECT_EQ(e.errors, errs);
        }
    }
}

TEST(Tmc8100Faults, ShortDatagramIsReportedNotInterpreted) {
    Tmc8100Scenario sc;
    sc.getVersion(1, 0);
    auto w = sc.build();
    // Cut the capture in the middle of the second transfer: cs stays low at the end.
    const auto& t = sc.transfers()[1];
    w.end = Tick(t.cs_low_ns + 500 + 376 * 10);
    std::erase_if(w.edges, [&](const Edge& e) { return e.t > w.end; });
    registerDecoders();
    auto cut = only(decodeWaveform(w, {DecoderRequest{"tmc8100", {}, {}}}), "tmc8100");
    ASSERT_EQ(cut.size(), 2u);
    EXPECT_EQ(show(*cut[1].get("name")), "\"unknown\"");
    EXPECT_EQ(cut[1].errors, std::vector<std::string>{"short_frame"});
}

TEST(Tmc8100Faults, HostThatNeverReadsDoesNotHoldTheOutputBack) {
    // Ten read commands and no reads: each is reported incomplete, the later ones as sent
    // with replies pending, and the waiting queue stays short (at most four commands), so
    // the session can release events while the capture goes on.
    Tmc8100Scenario sc;
    for (int i = 0; i < 10; ++i)
        sc.transfer(0x80000000u, 0);
    auto events = only(decode(sc), "tmc8100");
    ASSERT_EQ(events.size(), 20u);
    int reads = 0, pending = 0;
    for (std::size_t i = 0; i < events.size(); ++i) {
        if (events[i].type == "encoder_read") {
            ++reads;
            EXPECT_EQ(events[i].errors, std::vector<std::string>{"incomplete"});
            // Each read is reported right after its own command (time order by start).
            EXPECT_EQ(events[i - 1].type, "command");
            EXPECT_EQ(events[i - 1].start, events[i].start);
        } else if (events[i].hasError("replies_pending")) {
            ++pending;
        }
    }
    EXPECT_EQ(reads, 10);
    EXPECT_EQ(pending, 9);

    // Fed directly, the decoder's watermark (what the session may release up to) trails
    // the last command by at most four commands, not back to the first.
    registerDecoders();
    auto dec = Registry::instance().create("tmc8100", {});
    struct Sink : EventSink {
        void onEvent(Event&&) override {}
    } sink;
    Waveform w = sc.build();
    DecoderContext ctx;
    ctx.timebase = w.timebase;
    ctx.sink = &sink;
    ctx.initial_levels = {w.initial[0], w.initial[1], w.initial[2], w.initial[3], w.initial[4]};
    dec->start(ctx);
    dec->setSink(&sink);
    for (const Edge& e : w.edges)
        if (e.line < 5) dec->edge(e.t, int(e.line), e.level != 0);
    const Tick now = w.end;
    dec->advance(now);
    ScenarioExpect x{sc};
    EXPECT_GE(dec->watermark(now), x.start(6));
}
