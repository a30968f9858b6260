// The hint at the end of a decode (Decoder::advice): when no frame comes out clean the
// data width, the CRC options or the mapping is the likely cause, and the user is told
// what to check; a capture whose faults are in the traffic itself gets no hint.
#include <gtest/gtest.h>

#include <random>

#include <fmt/format.h>

#include "bissc_generator.h"
#include "bissc_test_util.h"
#include "capture/capture_reader.h"
#include "support/decode_events.h"

using namespace busdecode;
using namespace busdecode::test;

namespace {

// `frames` frames of 18-bit positions at 2 MHz; every `corrupt_every`-th one (0: none)
// with a wrong CRC.
Waveform frames18(int frames, int corrupt_every = 0) {
    BisscGenConfig cfg;
    cfg.clock_hz = 2e6;
    cfg.bits = 18;
    cfg.line_delay_ns = 150;
    cfg.timeout_ns = 15000;
    BisscGenerator gen(cfg);
    std::mt19937_64 rng{18};
    for (int i = 0; i < frames; ++i) {
        BisscFrameSpec f;
        f.data = rng() & ((1u << 18) - 1);
        f.corrupt_crc = corrupt_every > 0 && i % corrupt_every == 0;
        gen.addFrame(f);
    }
    return gen.build();
}

// The advice of a session decoding `w`, and (through `events`) what it printed.
std::vector<std::string> adviceFor(const Waveform& w,
                                   const std::map<std::string, std::string>& options,
                                   const std::string& ma = "MA", const std::string& sl = "SLO",
                                   std::vector<Event>* events = nullptr) {
    registerBissc();
    auto reader = memoryReader(w);
    DecoderRequest r;
    r.proto = "bissc";
    r.map = {{"ma", ma}, {"sl", sl}};
    r.options = options;
    CaptureFacts facts;
    auto decoded = test::decodeEvents(*reader, {r}, &facts);
    if (events) *events = std::move(decoded);
    return facts.advice;
}

bool has(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

}  // namespace

TEST(BisscAdvice, NoneForCleanTraffic) {
    const Waveform w = frames18(20);
    EXPECT_TRUE(adviceFor(w, {{"bits", "18"}}).empty());
    EXPECT_TRUE(adviceFor(w, {{"bits", "auto"}}).empty());
}

TEST(BisscAdvice, NoneWhenSomeFramesAreBadInTheTraffic) {
    // Every other frame with a wrong CRC: faults of the traffic, not of the options.
    std::vector<Event> events;
    EXPECT_TRUE(adviceFor(frames18(20, 2), {{"bits", "18"}}, "MA", "SLO", &events).empty());
    int crc_errors = 0;
    for (const auto& e : events)
        crc_errors += e.hasError("crc");
    EXPECT_EQ(crc_errors, 10);
}

TEST(BisscAdvice, AWidthTooShortOrTooLongIsPointedAt) {
    for (const std::string bits : {"12", "26"}) {
        SCOPED_TRACE(bits);
        const auto advice = adviceFor(frames18(20), {{"bits", bits}});
        ASSERT_EQ(advice.size(), 1u);
        EXPECT_TRUE(has(advice[0], "bissc: ")) << advice[0];
        EXPECT_TRUE(has(advice[0], "came out clean")) << advice[0];
        EXPECT_TRUE(has(advice[0], "with bits=" + bits + ":")) << advice[0];
        EXPECT_TRUE(has(advice[0], "--opt bits=auto")) << advice[0];
    }
    // Too long: the master stops clocking before the frame's end, no frame is complete.
    EXPECT_TRUE(has(adviceFor(frames18(20), {{"bits", "26"}})[0], "none of the 20 answered"));
}

TEST(BisscAdvice, AWrongCrcPolynomialLeavesOnlyChanceCleanFrames) {
    // At the right width, a wrong polynomial still passes a frame now and then.
    const auto advice = adviceFor(frames18(64), {{"bits", "18"}, {"crc_poly", "0x25"}});
    ASSERT_EQ(advice.size(), 1u);
    EXPECT_TRUE(has(advice[0], " of the 64 answered frames came out clean")) << advice[0];
    EXPECT_TRUE(has(advice[0], "the CRC options")) << advice[0];
}

TEST(BisscAdvice, SwappedLinesAreNamed) {
    // SL's changes start frames that no answer follows.
    const auto advice = adviceFor(frames18(5), {{"bits", "18"}}, "SLO", "MA");
    ASSERT_EQ(advice.size(), 1u);
    EXPECT_TRUE(has(advice[0], "no frame got an answer from the slave")) << advice[0];
    EXPECT_TRUE(has(advice[0], "mapped to the right signals")) << advice[0];
    // The width finder passes it on: no width helps there.
    const auto automatic = adviceFor(frames18(5), {{"bits", "auto"}}, "SLO", "MA");
    EXPECT_EQ(automatic, advice);
}

TEST(BisscAdvice, TheHintCountsEveryChangeOfBothLines) {
    // With no frame answered, every edge is outside a frame's data, whichever path took
    // it (onMa(), onSl(), or the clocks before an ACK, takeAckWaitEdge()): the hint's
    // counts are the lines' own.
    const Waveform w = frames18(5);
    std::size_t changes[2] = {0, 0};
    for (const Edge& e : w.edges)
        ++changes[e.line];
    ASSERT_GT(changes[0], 100u);
    const auto advice = adviceFor(w, {{"bits", "18"}}, "SLO", "MA");
    ASSERT_EQ(advice.size(), 1u);
    // Swapped: the decoder's MA is the slave's line (line 1), its SL the clock (line 0).
    EXPECT_TRUE(
        has(advice[0], fmt::format("MA changed {} times, SL {} times", changes[1], changes[0])))
        << advice[0];
}

TEST(BisscAdvice, NoWidthFitsWithoutACrc) {
    // bits=auto needs a CRC to tell widths apart: without one nothing fits, and the
    // hint says so instead of proposing bits=auto again.
    const auto advice = adviceFor(frames18(10), {{"bits", "auto"}, {"crc_bits", "0"}});
    ASSERT_EQ(advice.size(), 1u);
    EXPECT_TRUE(has(advice[0], "no data width from 1 to 64 gives a clean frame")) << advice[0];
    EXPECT_FALSE(has(advice[0], "bits=auto")) << advice[0];
    // A fixed width without a CRC cannot be judged: no hint.
    EXPECT_TRUE(adviceFor(frames18(10), {{"bits", "18"}, {"crc_bits", "0"}}).empty());
}

TEST(BisscAdvice, TheRestOfAFrameTheCaptureStartsInIsSkipped) {
    // 26 bits at 1 MHz, the capture started anywhere in the first frame: no frame is made
    // up of its rest (no early_ack, no short frame with invented fields); every frame
    // after it comes out whole, and the hint says the start was skipped.
    BisscGenerator gen(BisscGenConfig{});
    BisscFrameSpec f;
    for (int i = 0; i < 4; ++i) {
        f.data = 0x1234567u + std::uint64_t(i) * 0x10101u;
        gen.addFrame(f);
    }
    const Waveform whole = gen.build();
    const auto& truth = gen.frames();
    const Tick step = whole.timebase.fromNs(250);
    for (Tick cut = truth[0].start + 1; cut < truth[1].start; cut += step) {
        SCOPED_TRACE(cut);
        std::vector<Event> frames;
        const auto advice = adviceFor(startingAt(whole, cut), {}, "MA", "SLO", &frames);
        frames = ofType(frames, "frame");
        ASSERT_EQ(frames.size(), truth.size() - 1);
        for (std::size_t i = 0; i < frames.size(); ++i) {
            EXPECT_EQ(frames[i].start, truth[i + 1].start) << i;
            EXPECT_TRUE(frames[i].errors.empty()) << i << " " << frames[i].summary;
            EXPECT_EQ(intField(frames[i], "position"), 0x1234567 + int(i + 1) * 0x10101) << i;
        }
        for (const auto& a : advice)
            EXPECT_NE(a.find("the capture starts inside a frame"), std::string::npos) << a;
    }
}
