// `--opt bits=auto`: the width found from the first frames' CRCs gives exactly the
// events of `--opt bits=N`, for moving and standing encoders, short and long captures.
#include <gtest/gtest.h>

#include <random>

#include "bissc_generator.h"
#include "bissc_test_util.h"
#include "bissc_width_finder.h"
#include "capture/capture_reader.h"
#include "core/registry.h"
#include "sinks/event_format.h"

using namespace busdecode;
using namespace busdecode::test;

namespace {

std::string asJsonl(const std::vector<Event>& events, const Timebase& tb) {
    std::string out;
    for (const auto& e : events)
        out += eventToJson(e, tb) + "\n";
    return out;
}

// `frames` frames of `bits` bits at 2 MHz, positions from `position(i)`; the master
// clocks `extra_clocks` past the stop bit, or stops after `truncate_after` rising edges.
template <class Position>
Waveform capture(int bits, int frames, Position position, int extra_clocks = 0,
                 int truncate_after = -1) {
    BisscGenConfig cfg;
    cfg.clock_hz = 2e6;
    cfg.bits = bits;
    cfg.line_delay_ns = 120;
    cfg.timeout_ns = 15000;
    cfg.seed = std::uint32_t(bits);
    BisscGenerator gen(cfg);
    for (int i = 0; i < frames; ++i) {
        BisscFrameSpec f;
        f.data = position(i);
        f.ne = i % 7 != 3;  // nE active now and then: still a clean frame for the finder
        f.extra_clocks = extra_clocks;
        f.truncate_after = truncate_after;
        gen.addFrame(f);
    }
    return gen.build();
}

std::uint64_t mask(int bits) {
    return bits >= 64 ? ~0ull : (1ull << bits) - 1;
}

void expectSameAsFixedWidth(const Waveform& w, int bits) {
    const auto fixed = decodeBissc(w, {{"bits", std::to_string(bits)}});
    const auto automatic = decodeBissc(w, {{"bits", "auto"}});
    ASSERT_FALSE(ofType(fixed, "frame").empty());
    ASSERT_FALSE(ofType(automatic, "frame").empty());
    EXPECT_EQ(intField(ofType(automatic, "frame").front(), "bits"), bits);
    EXPECT_EQ(asJsonl(automatic, w.timebase), asJsonl(fixed, w.timebase));
}

// The events of a session whose only sink reads the events' fields or summaries as
// given: text output reads summaries alone, jsonl fields alone.
std::vector<Event> decodeFor(const Waveform& w, const std::string& bits, bool fields,
                             bool summaries) {
    registerBissc();
    struct Reading : OutputSink {
        bool fields, summaries;
        std::vector<Event> events;
        void onEvent(const Event& e, const CaptureFacts&) override { events.push_back(e); }
        bool readsFields() const override { return fields; }
        bool readsSummaries() const override { return summaries; }
    } sink;
    sink.fields = fields;
    sink.summaries = summaries;
    auto reader = memoryReader(w);
    DecoderRequest r;
    r.proto = "bissc";
    r.map = {{"ma", "MA"}, {"sl", "SLO"}};
    r.options = {{"bits", bits}};
    Session s({r}, *reader, "memory");
    s.addSink(&sink);
    s.run();
    return sink.events;
}

}  // namespace

TEST(BisscWidth, AutoFindsEveryWidthOfAMovingEncoder) {
    for (int bits : {1, 8, 13, 18, 26, 32, 36, 48, 64}) {
        SCOPED_TRACE(bits);
        std::mt19937_64 rng{std::uint64_t(bits)};
        expectSameAsFixedWidth(capture(bits, 12, [&](int) { return rng() & mask(bits); }), bits);
    }
}

TEST(BisscWidth, AutoFindsTheWidthOfAStandingEncoder) {
    // Every frame the same: a shorter width that passes by chance passes in every frame,
    // and the tie goes to the longer width, the true one.
    for (std::uint64_t pos : {0x0ull, 0xFFFFFFFFull, 0x12345678ull, 0x80000001ull}) {
        SCOPED_TRACE(pos);
        expectSameAsFixedWidth(capture(32, 6, [&](int) { return pos; }), 32);
    }
}

TEST(BisscWidth, AutoFromASingleFrame) {
    // A capture of one frame (as the MB5U captures are): it ends in the slave's timeout,
    // and still counts. In these frames a shorter width passes too (12 and 9 bits: CRC
    // and stop bit right by chance); the tie goes to the longer one, the true width.
    for (std::uint64_t pos : {0x9B05C2F1ull, 0x8B6EB381ull, 0x2F70115Aull}) {
        SCOPED_TRACE(pos);
        expectSameAsFixedWidth(capture(32, 1, [&](int) { return pos; }), 32);
    }
}

TEST(BisscWidth, AutoWhenTheCaptureEndsInTheTimeout) {
    // The capture stops while SL is still low after the stop bit: the frame is complete,
    // closed only by the end of the capture, and counts for the width.
    Waveform w = capture(32, 1, [](int) { return 0x8B6EB381ull; });
    ASSERT_EQ(w.edges.back().line, 1u);  // SL rising at the end of the timeout
    ASSERT_EQ(w.edges.back().level, 1);
    w.end = w.edges.back().t - 1;
    w.edges.pop_back();
    expectSameAsFixedWidth(w, 32);
}

TEST(BisscWidth, AutoWithClocksPastTheStopBit) {
    // The MB5U clocks four bits past the stop bit (the real RESOLUTE captures).
    std::mt19937_64 rng(5);
    expectSameAsFixedWidth(capture(
                               32, 8, [&](int) { return rng() & mask(32); }, 4),
                           32);
}

// Feeds `w` edge by edge to a width finder until it has chosen; returns the edges fed
// and the frames it had output by then.
struct Fed {
    std::size_t edges = 0;
    int width = 0;
    int frames = 0;
};
Fed feedUntilDecided(const Waveform& w) {
    registerBissc();
    const auto* factory = Registry::instance().find("bissc");
    std::map<std::string, std::string> given{{"bits", "auto"}};
    auto decoder = factory->create(Options::resolve(factory->info(), given));
    auto* finder = dynamic_cast<BisscWidthFinder*>(decoder.get());
    if (!finder) return {};
    struct Count : EventSink {
        int frames = 0;
        void onEvent(Event&& e) override { frames += e.type == "frame"; }
    } sink;
    DecoderContext ctx;
    ctx.timebase = w.timebase;
    ctx.initial_levels = {w.initial[0], w.initial[1]};
    ctx.sink = &sink;
    finder->start(ctx);
    Fed out;
    for (; out.edges < w.edges.size() && finder->width() == 0; ++out.edges) {
        const Edge& e = w.edges[out.edges];
        finder->edge(e.t, int(e.line), e.level != 0);
    }
    out.width = finder->width();
    out.frames = sink.frames;
    return out;
}

TEST(BisscWidth, MovingEncoderIsDecidedAfterAFewFrames) {
    // One width stands alone after the first try: the held frames come out at once, and
    // the events are those of the fixed width, the held ones and the later ones alike.
    std::mt19937_64 rng(9);
    const Waveform w = capture(26, 400, [&](int) { return rng() & mask(26); });
    ASSERT_GT(w.edges.size(), BisscWidthFinder::kLearnEdges);
    expectSameAsFixedWidth(w, 26);
    const Fed fed = feedUntilDecided(w);
    EXPECT_EQ(fed.edges, BisscWidthFinder::kTryEvery);
    EXPECT_EQ(fed.width, 26);
    EXPECT_GT(fed.frames, 10);  // out before the capture ends
}

TEST(BisscWidth, StandingEncoderWaitsForTheWholeSpan) {
    // Every frame the same, and a shorter width (12) fits them too: no early decision;
    // the full span is held, and the tie goes to the true width.
    const Waveform w = capture(32, 400, [](int) { return 0x8B6EB381ull; });
    ASSERT_GT(w.edges.size(), BisscWidthFinder::kLearnEdges);
    expectSameAsFixedWidth(w, 32);
    const Fed fed = feedUntilDecided(w);
    EXPECT_EQ(fed.edges, BisscWidthFinder::kLearnEdges);
    EXPECT_EQ(fed.width, 32);
    EXPECT_GT(fed.frames, 100);
}

TEST(BisscWidth, WithoutACleanFrameTheDefaultWidth) {
    // Frames the master cuts short after 10 clocks, too few for a CRC under any width
    // (a wrong CRC would not do: some width passes it by chance): the default, 26.
    const Waveform w = capture(
        20, 3, [](int i) { return 0x5A5A5u + std::uint64_t(i); }, 0, 10);
    const auto frames = ofType(decodeBissc(w, {{"bits", "auto"}}), "frame");
    ASSERT_EQ(frames.size(), 3u);
    for (const auto& f : frames) {
        EXPECT_EQ(intField(f, "bits"), 26);
        EXPECT_TRUE(f.hasError("short_frame"));
    }
}

TEST(BisscWidth, OtherOptionsAreStillChecked) {
    registerBissc();
    const auto* factory = Registry::instance().find("bissc");
    ASSERT_NE(factory, nullptr);
    std::map<std::string, std::string> given{
        {"bits", "auto"}, {"st_bits", "40"}, {"mt_bits", "30"}};
    EXPECT_THROW(factory->create(Options::resolve(factory->info(), given)), InputError);
    given = {{"bits", "auto"}, {"mt_bits", "12"}};  // st_bits auto: the rest of the width
    EXPECT_NO_THROW(factory->create(Options::resolve(factory->info(), given)));
}

TEST(BisscWidth, TextOutputLeavesFieldsOutAndStillFindsTheWidth) {
    // With only text output, frames come without fields (their summary says it all), and
    // bits=auto still finds the width. 18 bits, not the default 26, so that a finder
    // seeing no clean frame would show.
    std::mt19937_64 rng{18};
    const Waveform w = capture(18, 12, [&](int) { return rng() & mask(18); });
    const auto fixed = decodeBissc(w, {{"bits", "18"}});
    for (const std::string bits : {"18", "auto"}) {
        SCOPED_TRACE(bits);
        const auto text = decodeFor(w, bits, false, true);
        ASSERT_EQ(text.size(), fixed.size());
        for (std::size_t i = 0; i < text.size(); ++i) {
            EXPECT_EQ(eventToText(text[i], w.timebase), eventToText(fixed[i], w.timebase));
            EXPECT_EQ(text[i].errors, fixed[i].errors);
            if (text[i].type == "frame") {
                EXPECT_TRUE(text[i].fields.empty());
                EXPECT_EQ(fixed[i].fields.size(), 20u);
            }
        }
    }
}

TEST(BisscWidth, JsonlOutputLeavesSummariesOut) {
    // With only sinks that read fields (jsonl, verify, Python), frames come without their
    // summary and with the same fields.
    std::mt19937_64 rng{26};
    const Waveform w = capture(26, 12, [&](int) { return rng() & mask(26); });
    const auto both = decodeBissc(w, {{"bits", "26"}});
    const auto json = decodeFor(w, "26", true, false);
    EXPECT_EQ(asJsonl(json, w.timebase), asJsonl(both, w.timebase));
    ASSERT_EQ(json.size(), both.size());
    for (std::size_t i = 0; i < json.size(); ++i) {
        if (json[i].type != "frame") continue;
        EXPECT_EQ(json[i].summary, "");
        EXPECT_NE(both[i].summary, "");
    }
}
