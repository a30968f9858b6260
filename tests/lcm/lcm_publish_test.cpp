// Publishing on memq://: one typed message per event on the contract's channel, fields
// equal to the event's, the annotation with the event's text and JSON, nulls, plugins'
// events, the bounded queue (block and drop), and clear errors for bad URLs.
#include <gtest/gtest.h>

#include <unistd.h>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <cstdlib>
#include <lcm/lcm-cpp.hpp>
#include <mutex>
#include <thread>

#include "busdecode_lcm/bissc_frame_t.hpp"
#include "busdecode_lcm/decode_status_t.hpp"
#include "busdecode_lcm/event_annotation_t.hpp"
#include "busdecode_lcm/event_fields_t.hpp"
#include "busdecode_lcm/ssi_frame_t.hpp"
#include "busdecode_lcm/tmc8100_encoder_read_t.hpp"
#include "core/options.h"
#include "lcm/lcm_channels.h"
#include "lcm/lcm_messages.h"
#include "lcm/lcm_publisher.h"
#include "lcm/lcm_sink.h"
#include "lcm_message_view.h"
#include "sinks/event_format.h"
#include "value_compare.h"

namespace busdecode {
namespace {

using test::Collector;

// 24 MHz sampling: ticks are not nanoseconds, so start_ns/end_ns must be converted.
CaptureFacts facts24MHz() {
    CaptureFacts f;
    f.file = "hand-made.vcd";
    f.format = "vcd";
    f.timebase = Timebase::fromSampleRate(24'000'000);
    f.protos = {"ssi", "bissc"};
    return f;
}

Event make(std::string proto, std::string type, Tick start, Tick end,
           std::vector<std::pair<std::string, Value>> fields) {
    Event e;
    e.proto = std::move(proto);
    e.type = std::move(type);
    e.instance = e.proto;
    e.start = start;
    e.end = end;
    for (auto& [k, v] : fields)
        e.set(k, std::move(v));
    e.summary = "hand-made " + e.type;
    return e;
}

using I = std::int64_t;
using U = std::uint64_t;

// One event of every kind of the contract's table, with every contract field set.
std::vector<Event> everyKind() {
    return {
        make("ssi", "frame", 2400, 2900,
             {{"raw", I(0x1ABCDEF)},
              {"bits", I(25)},
              {"position", I(0xABCDEF)},
              {"st", I(0xCDEF)},
              {"mt", I(0xAB)},
              {"angle", 289.3},
              {"repeats", I(2)},
              {"repeat_match", true},
              {"clock_hz", 1.0e6},
              {"tm_ns", 20041.5}}),
        make("bissc", "frame", 3000, 3500,
             {{"position", I(0x2345678)},
              {"st", I(0x5678)},
              {"mt", I(0x234)},
              {"nE", I(1)},
              {"nW", I(0)},
              {"crc_rx", I(0x2A)},
              {"crc_ok", false},
              {"cds", I(1)},
              {"cdm", I(0)},
              {"line_delay_ns", 291.7},
              {"proc_cycles", I(3)},
              {"clock_hz", 2.5e6},
              {"timeout_ns", 15000.0}}),
        make("bissc", "register", 3600, 90000,
             {{"op", std::string("read")},
              {"id", I(0)},
              {"address", I(0x42)},
              {"data", std::vector<I>{0x12, 0x34}},
              {"crc_ok", true}}),
        make("bissc", "command", 91000, 99000, {{"id", I(3)}, {"command", I(2)}, {"crc_ok", true}}),
        make("spi", "transfer", 100000, 100800,
             {{"mosi", U(0xF00000000000000Full)}, {"miso", U(0x123456)}, {"bits", I(64)}}),
        make("tmc8100", "command", 101000, 101200,
             {{"code", I(0x01)}, {"name", std::string("read_encoder")}}),
        make("tmc8100", "reply", 101300, 101500,
             {{"tag", I(0x81)}, {"value", I(0xABCDE)}, {"meaning", std::string("position")}}),
        make("tmc8100", "encoder_read", 101000, 101500,
             {{"gray", I(0x3F)},
              {"binary", I(0x2A)},
              {"flags", I(0x5)},
              {"consistent", true},
              {"ssi_match", false}}),
        make("uart", "byte", 102000, 104500, {{"value", I(0x55)}, {"line", std::string("tx")}}),
        make("tmcl", "command", 105000, 120000,
             {{"address", I(1)},
              {"command", I(4)},
              {"mnemonic", std::string("MVP")},
              {"type_no", I(0)},
              {"motor", I(0)},
              {"value", I(-12345)},
              {"checksum_ok", true}}),
        make("tmcl", "reply", 121000, 136000,
             {{"reply_address", I(2)},
              {"module_address", I(1)},
              {"status", I(100)},
              {"status_text", std::string("ok")},
              {"command", I(4)},
              {"value", I(-12345)},
              {"checksum_ok", false}}),
    };
}

// Runs the events through a sink on one shared memq:// instance and collects it all.
struct MemqRun {
    std::shared_ptr<lcm::LCM> lc = openLcm("memq://");
    Collector got{*lc};
    LcmSinkCounts counts;

    // `ended`: false stands for a run interrupted inside its capture (no end()).
    void publish(const std::vector<Event>& events, LcmSinkOptions opt = {}, bool ended = true) {
        {
            LcmSink sink(lc, "memq://", std::move(opt));
            CaptureFacts f = facts24MHz();
            sink.begin(f);
            for (const Event& e : events)
                sink.onEvent(e, f);
            f.end = 200000;
            if (ended) sink.end(f);
            counts = sink.counts();
        }
        got.drain(*lc);
    }
};

void expectMessageEqualsEvent(const test::MessageView& v, const Event& e, const Timebase& tb) {
    SCOPED_TRACE(v.channel);
    EXPECT_EQ(v.channel, lcmChannelFor(e.proto, e.type));
    EXPECT_EQ(v.start_ns, tb.toNs(e.start));
    EXPECT_EQ(v.end_ns, tb.toNs(e.end));
    EXPECT_EQ(v.instance, e.instance);
    EXPECT_EQ(v.errors, e.errors);
    EXPECT_GT(v.utime, 1'600'000'000'000'000);  // wall clock, in us since 1970
    for (const auto& [key, value] : v.fields)
        EXPECT_EQ(test::compareValues(value, e.get(key)), "") << "field " << key;
}

TEST(LcmChannels, AreDecodeProtoTypeInUpperCase) {
    EXPECT_EQ(lcmChannelFor("bissc", "frame"), "DECODE_BISSC_FRAME");
    EXPECT_EQ(lcmChannelFor("tmc8100", "encoder_read"), "DECODE_TMC8100_ENCODER_READ");
    EXPECT_EQ(lcmChannelFor("my-bus", "x.y"), "DECODE_MY_BUS_X_Y");
}

TEST(LcmChannels, EveryContractKindHasATypedMessage) {
    for (const Event& e : everyKind())
        EXPECT_TRUE(hasTypedLcmMessage(e.proto, e.type)) << e.proto;
    EXPECT_FALSE(hasTypedLcmMessage("bissc", "idle"));
    EXPECT_FALSE(hasTypedLcmMessage("myplug", "frame"));
}

TEST(LcmPublish, OneTypedMessagePerEventWithTheEventsFields) {
    std::vector<Event> events = everyKind();
    MemqRun run;
    run.publish(events);
    ASSERT_EQ(run.counts.published, events.size());
    EXPECT_EQ(run.counts.dropped, 0u);

    Timebase tb = facts24MHz().timebase;
    std::map<std::string, std::size_t> next;  // per channel, the next message to compare
    for (std::size_t i = 0; i < events.size(); ++i) {
        const Event& e = events[i];
        std::string ch = lcmChannelFor(e.proto, e.type);
        const auto& msgs = run.got.byChannel[ch];
        ASSERT_LT(next[ch], msgs.size()) << ch;
        const auto& bytes = msgs[next[ch]++];
        auto v = test::viewEventMessage(ch, bytes.data(), int(bytes.size()));
        ASSERT_TRUE(v);
        EXPECT_EQ(v->seq, std::int64_t(i));
        EXPECT_EQ(v->fields.size(), e.fields.size()) << ch << ": every contract field is carried";
        expectMessageEqualsEvent(*v, e, tb);
    }
    for (auto& [ch, n] : next)
        EXPECT_EQ(run.got.byChannel[ch].size(), n) << "one message per event on " << ch;
}

TEST(LcmPublish, AnnotationCarriesEveryEventsTextAndJson) {
    std::vector<Event> events = everyKind();
    events[1].error("crc");
    MemqRun run;
    run.publish(events);
    auto notes = run.got.decodeAll<busdecode_lcm::event_annotation_t>(kLcmEventsChannel);
    ASSERT_EQ(notes.size(), events.size());
    Timebase tb = facts24MHz().timebase;
    for (std::size_t i = 0; i < events.size(); ++i) {
        SCOPED_TRACE(i);
        EXPECT_EQ(notes[i].seq, std::int64_t(i));
        EXPECT_EQ(notes[i].proto, events[i].proto);
        EXPECT_EQ(notes[i].type, events[i].type);
        EXPECT_EQ(notes[i].channel, lcmChannelFor(events[i].proto, events[i].type));
        EXPECT_EQ(notes[i].text, eventToText(events[i], tb));
        EXPECT_EQ(notes[i].json, eventToJson(events[i], tb));
        EXPECT_EQ(notes[i].start_ns, tb.toNs(events[i].start));
        EXPECT_EQ(notes[i].errors, events[i].errors);
    }
    // The typed message of each event comes just before its annotation.
    ASSERT_GE(run.got.order.size(), 2 * events.size());
    std::vector<std::string> event_channels;
    for (const auto& ch : run.got.order)
        if (ch != kLcmStatusChannel) event_channels.push_back(ch);
    for (std::size_t i = 0; i < events.size(); ++i) {
        EXPECT_EQ(event_channels[2 * i], lcmChannelFor(events[i].proto, events[i].type));
        EXPECT_EQ(event_channels[2 * i + 1], kLcmEventsChannel);
    }
}

TEST(LcmPublish, TheSinkReadsTheSummariesItsAnnotationsCarry) {
    // An annotation's text is text output's line, the event's summary: with LCM as the
    // only sink, decoders must still set summaries (and fields, for the messages).
    LcmSink sink(openLcm("memq://"), "memq://", {});
    EXPECT_TRUE(sink.readsSummaries());
    EXPECT_TRUE(sink.readsFields());
}

TEST(LcmPublish, NullAndMissingFieldsAreListedAndFlagged) {
    Event ssi = everyKind()[0];
    ssi.set("tm_ns", Null{});
    ssi.error("short_frame");
    Event biss = make("bissc", "frame", 10, 20, {{"position", I(5)}, {"line_delay_ns", Null{}}});
    Event enc = everyKind()[7];
    enc.fields.erase(enc.fields.end() - 1);  // no ssi_match: SSI not decoded in this pass
    MemqRun run;
    run.publish({ssi, biss, enc});

    auto s = run.got.decodeAll<busdecode_lcm::ssi_frame_t>("DECODE_SSI_FRAME");
    ASSERT_EQ(s.size(), 1u);
    EXPECT_FALSE(s[0].has_tm_ns);
    EXPECT_TRUE(std::isnan(s[0].tm_ns));
    EXPECT_EQ(s[0].null_fields, std::vector<std::string>{"tm_ns"});
    EXPECT_EQ(s[0].errors, std::vector<std::string>{"short_frame"});
    EXPECT_EQ(s[0].raw, 0x1ABCDEF);

    auto b = run.got.decodeAll<busdecode_lcm::bissc_frame_t>("DECODE_BISSC_FRAME");
    ASSERT_EQ(b.size(), 1u);
    EXPECT_EQ(b[0].position, 5);
    EXPECT_TRUE(std::isnan(b[0].line_delay_ns));
    // Every contract field but position is null or missing.
    EXPECT_EQ(b[0].num_null_fields, 12);
    EXPECT_NE(std::find(b[0].null_fields.begin(), b[0].null_fields.end(), "line_delay_ns"),
              b[0].null_fields.end());

    auto t =
        run.got.decodeAll<busdecode_lcm::tmc8100_encoder_read_t>("DECODE_TMC8100_ENCODER_READ");
    ASSERT_EQ(t.size(), 1u);
    EXPECT_FALSE(t[0].has_ssi_match);
    EXPECT_EQ(t[0].num_null_fields, 0);
    EXPECT_TRUE(t[0].consistent);
}

TEST(LcmPublish, EventsWithoutATypedMessageGoToTheGenericMessageAndTheAnnotation) {
    Event plug = make("myplug", "burst", 100, 200,
                      {{"count", I(3)},
                       {"ratio", 0.25},
                       {"ok", true},
                       {"name", std::string("x\"y")},
                       {"big", U(0xFFFFFFFFFFFFFFFFull)},
                       {"bytes", std::vector<I>{1, 2, 3}},
                       {"unknown", Null{}}});
    plug.instance = "myplug#2";
    MemqRun run;
    run.publish({plug});
    auto g = run.got.decodeAll<busdecode_lcm::event_fields_t>("DECODE_MYPLUG_BURST");
    ASSERT_EQ(g.size(), 1u);
    EXPECT_EQ(g[0].proto, "myplug");
    EXPECT_EQ(g[0].type, "burst");
    EXPECT_EQ(g[0].instance, "myplug#2");
    ASSERT_EQ(g[0].num_fields, 7);
    const auto& bytes = run.got.byChannel["DECODE_MYPLUG_BURST"][0];
    auto v = test::viewEventMessage("DECODE_MYPLUG_BURST", bytes.data(), int(bytes.size()));
    ASSERT_TRUE(v);
    expectMessageEqualsEvent(*v, plug, facts24MHz().timebase);
    EXPECT_EQ(g[0].fields[4].kind, busdecode_lcm::event_field_t::KIND_UINT);
    EXPECT_EQ(g[0].fields[4].json, "18446744073709551615");
    EXPECT_EQ(g[0].fields[5].json, "[1,2,3]");
    auto notes = run.got.decodeAll<busdecode_lcm::event_annotation_t>(kLcmEventsChannel);
    ASSERT_EQ(notes.size(), 1u);
    EXPECT_EQ(notes[0].channel, "DECODE_MYPLUG_BURST");
}

TEST(LcmPublish, StatusMessagesFrameTheRunWithCounts) {
    MemqRun run;
    run.publish(everyKind());
    auto st = run.got.decodeAll<busdecode_lcm::decode_status_t>(kLcmStatusChannel);
    ASSERT_EQ(st.size(), 4u);
    EXPECT_EQ(st[0].state, "start");
    EXPECT_EQ(st[1].state, "begin");
    EXPECT_EQ(st[1].file, "hand-made.vcd");
    EXPECT_EQ(st[1].protos, (std::vector<std::string>{"ssi", "bissc"}));
    EXPECT_EQ(st[2].state, "end");
    EXPECT_EQ(st[2].events, 11);
    EXPECT_EQ(st[2].published, 11);
    EXPECT_EQ(st[2].capture_ns, Timebase::fromSampleRate(24'000'000).toNs(200000));
    EXPECT_EQ(st[3].state, "done");
    EXPECT_EQ(st[3].file, "hand-made.vcd");
    EXPECT_EQ(run.got.order.back(), kLcmStatusChannel) << "end comes after every event";
}

TEST(LcmPublish, AnInterruptedCaptureIsEndedBeforeTheRunIsDone) {
    MemqRun run;
    const auto events = everyKind();
    run.publish(events, {}, false);
    auto st = run.got.decodeAll<busdecode_lcm::decode_status_t>(kLcmStatusChannel);
    ASSERT_EQ(st.size(), 4u);
    EXPECT_EQ(st[2].state, "end");
    EXPECT_EQ(st[2].events, 11);
    EXPECT_EQ(st[2].capture_ns, Timebase::fromSampleRate(24'000'000).toNs(events.back().end));
    EXPECT_EQ(st[3].state, "done");
}

// A publisher that can be held, to stand for a consumer side that can't keep up.
struct Gate {
    std::mutex mu;
    std::condition_variable cv;
    bool open = false;
    std::atomic<int> waiting{0};
    void pass() {
        std::unique_lock lock(mu);
        waiting++;
        cv.wait(lock, [&] { return open; });
    }
    void release() {
        {
            std::lock_guard lock(mu);
            open = true;
        }
        cv.notify_all();
    }
};

std::vector<Event> manyFrames(int n) {
    std::vector<Event> out;
    for (int i = 0; i < n; ++i)
        out.push_back(make("ssi", "frame", i * 100, i * 100 + 50, {{"raw", I(i)}}));
    return out;
}

TEST(LcmQueue, DropModeCountsWhatAFullQueueLosesAndReportsIt) {
    auto gate = std::make_shared<Gate>();
    LcmSinkOptions opt;
    opt.queue_capacity = 2;
    opt.drop_when_full = true;
    opt.before_publish = [gate] { gate->pass(); };
    char* report_buf = nullptr;
    std::size_t report_len = 0;
    opt.report = open_memstream(&report_buf, &report_len);

    auto lc = openLcm("memq://");
    Collector got(*lc);
    CaptureFacts f = facts24MHz();
    LcmSinkCounts counts;
    {
        LcmSink sink(lc, "memq://", opt);
        sink.begin(f);
        for (const Event& e : manyFrames(10))
            sink.onEvent(e, f);  // never waits
        counts = sink.counts();
        EXPECT_EQ(counts.events, 10u);
        // At most one event is held by the publisher and two wait in the queue.
        EXPECT_GE(counts.dropped, 7u);
        gate->release();
        sink.end(f);
        counts = sink.counts();
    }
    std::fclose(opt.report);
    std::string report(report_buf, report_len);
    std::free(report_buf);
    got.drain(*lc);
    EXPECT_EQ(counts.published + counts.dropped, 10u);
    EXPECT_EQ(got.byChannel["DECODE_SSI_FRAME"].size(), counts.published);
    EXPECT_NE(report.find("dropped " + std::to_string(counts.dropped) + " of 10 events"),
              std::string::npos)
        << report;
}

TEST(LcmQueue, BlockModeWaitsAndLosesNothing) {
    auto gate = std::make_shared<Gate>();
    LcmSinkOptions opt;
    opt.queue_capacity = 2;
    opt.before_publish = [gate] { gate->pass(); };
    auto lc = openLcm("memq://");
    Collector got(*lc);
    CaptureFacts f = facts24MHz();
    LcmSink sink(lc, "memq://", opt);
    sink.begin(f);
    std::atomic<int> pushed{0};
    std::thread decoder([&] {
        for (const Event& e : manyFrames(10)) {
            sink.onEvent(e, f);
            pushed++;
        }
    });
    // The decoder can get at most capacity + 1 (held by the publisher) + 1 (being pushed)
    // ahead; it must not finish while the publisher is held.
    while (gate->waiting.load() == 0)
        std::this_thread::yield();
    EXPECT_LT(pushed.load(), 10);
    gate->release();
    decoder.join();
    sink.end(f);
    got.drain(*lc);
    EXPECT_EQ(sink.counts().dropped, 0u);
    auto frames = got.decodeAll<busdecode_lcm::ssi_frame_t>("DECODE_SSI_FRAME");
    ASSERT_EQ(frames.size(), 10u);
    for (int i = 0; i < 10; ++i)
        EXPECT_EQ(frames[i].raw, i) << "in order";
}

TEST(LcmQueue, ARateLimitPacesThePublisher) {
    LcmSinkOptions opt;
    opt.max_events_per_s = 200;  // one event every 5 ms
    MemqRun run;
    auto started = std::chrono::steady_clock::now();
    run.publish(manyFrames(21), opt);
    double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    EXPECT_GE(elapsed, 0.095) << "21 events at 200/s take at least 20 periods";
    EXPECT_EQ(run.got.byChannel["DECODE_SSI_FRAME"].size(), 21u);
}

TEST(LcmSinkStart, BadUrlIsAClearInputError) {
    try {
        makeLcmSink("bogus://nowhere");
        FAIL() << "no error";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("bogus://nowhere"), std::string::npos) << e.what();
    }
    EXPECT_THROW(makeLcmSink("udpm://999.1.2.3:7667"), InputError);
}

TEST(LcmSinkStart, EnvironmentIsValidated) {
    setenv("BUSDECODE_LCM_QUEUE", "many", 1);
    EXPECT_THROW(LcmSinkOptions::fromEnvironment("memq://"), InputError);
    setenv("BUSDECODE_LCM_QUEUE", "16", 1);
    setenv("BUSDECODE_LCM_DROP", "1", 1);
    setenv("BUSDECODE_LCM_RATE", "0", 1);
    LcmSinkOptions o = LcmSinkOptions::fromEnvironment("");
    EXPECT_EQ(o.max_events_per_s, 0.0) << "BUSDECODE_LCM_RATE=0 lifts the udpm pace";
    EXPECT_EQ(o.queue_capacity, 16u);
    EXPECT_TRUE(o.drop_when_full);
    unsetenv("BUSDECODE_LCM_QUEUE");
    unsetenv("BUSDECODE_LCM_DROP");
    unsetenv("BUSDECODE_LCM_RATE");
    EXPECT_FALSE(LcmSinkOptions::fromEnvironment("memq://").drop_when_full);
    EXPECT_EQ(LcmSinkOptions::fromEnvironment("memq://").max_events_per_s, 0.0);
    EXPECT_EQ(LcmSinkOptions::fromEnvironment("").max_events_per_s,
              LcmSinkOptions::kDefaultUdpmEventsPerS);
    EXPECT_EQ(LcmSinkOptions::fromEnvironment("udpm://239.255.76.68:7668?ttl=0").max_events_per_s,
              LcmSinkOptions::kDefaultUdpmEventsPerS);
    setenv("BUSDECODE_LCM_RATE", "-3", 1);
    EXPECT_THROW(LcmSinkOptions::fromEnvironment(""), InputError);
    unsetenv("BUSDECODE_LCM_RATE");
}

TEST(LcmSinkStart, FileUrlWritesALogThatEventLogReads) {
    std::string path = "/tmp/busdecode_lcm_file_url_" + std::to_string(::getpid()) + ".lcmlog";
    {
        auto sink = makeLcmSink("file://" + path + "?mode=w");
        CaptureFacts f = facts24MHz();
        sink->begin(f);
        for (const Event& e : everyKind())
            sink->onEvent(e, f);
        sink->end(f);
    }
    lcm::LogFile log(path, "r");
    ASSERT_TRUE(log.good());
    int typed = 0, notes = 0;
    while (const lcm::LogEvent* ev = log.readNextEvent()) {
        if (ev->channel == kLcmEventsChannel)
            notes++;
        else if (ev->channel != kLcmStatusChannel)
            typed++;
    }
    EXPECT_EQ(typed, 11);
    EXPECT_EQ(notes, 11);
    std::remove(path.c_str());
}

}  // namespace
}  // namespace busdecode
