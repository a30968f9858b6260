// BiSS-C takes a frame's data edges in runs, with the frame's state in local variables
// (BisscDecoder::dataRun), from edges() and from edge(); its general path
// (edgeReference()) takes every edge through the LineSampler. All must decode every
// capture to the same events, bit for bit: the same samples, delays and periods,
// whatever the traffic, and wherever a block boundary cuts a run.
#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

#include "bissc_generator.h"
#include "bissc_random_capture.h"
#include "bissc_test_util.h"
#include "support/feed/direct_feed.h"

namespace busdecode::test {
namespace {

// Every event of `w` in full (times, fields, errors, summary), one JSON line each, and
// the decoder's advice (decodeDirectly()), fed as `feed` says (`block`: the block size
// for Feed::Blocks).
std::vector<std::string> decode(const Waveform& w, Feed feed, std::size_t block = 0,
                                const std::vector<int>& line_of_role = {0, 1}) {
    registerBissc();
    const auto* factory = Registry::instance().find("bissc");
    const Options options = Options::resolve(factory->info(), {{"bits", "26"}});
    return decodeDirectly(*factory, options, w, line_of_role, feed, block);
}

// `w` with its two lines swapped: SL on line 0, MA on line 1 (bound as {1, 0}), so that
// a line is not its role and the runs look the role up (FastPathHints::lines_are_roles).
Waveform swapLines(Waveform w) {
    std::swap(w.names[0], w.names[1]);
    std::swap(w.initial[0], w.initial[1]);
    for (Edge& e : w.edges)
        e = Edge(e.t, 1u - std::uint32_t(e.line), std::uint8_t(e.level));
    return w;
}

// `count` clean frames of random 26-bit positions.
void addPlainFrames(BisscGenerator& gen, int count, std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    for (int i = 0; i < count; ++i) {
        BisscFrameSpec f;
        f.data = rng() & ((1ull << 26) - 1);
        gen.addFrame(f);
    }
}

TEST(BisscBlocks, RunsDecodeAsEdgeByEdgeWhateverTheTraffic) {
    for (std::uint32_t seed = 1; seed <= 60; ++seed) {
        SCOPED_TRACE(::testing::Message() << "seed " << seed);
        const Waveform w = randomCapture(seed, 40);
        const std::vector<std::string> by_edge = decode(w, Feed::Reference);
        ASSERT_GT(by_edge.size(), 20u);
        // edge() one at a time (0), then edges() in blocks of 2, 7 and 16 384.
        for (const std::size_t block : {0, 2, 7, 16384}) {
            SCOPED_TRACE(::testing::Message() << "fed " << block);
            const std::vector<std::string> by_block =
                block == 0 ? decode(w, Feed::OneByOne) : decode(w, Feed::Blocks, block);
            ASSERT_EQ(by_block.size(), by_edge.size());
            for (std::size_t i = 0; i < by_edge.size(); ++i)
                ASSERT_EQ(by_block[i], by_edge[i]) << "event " << i;
        }
        // The lines swapped: blocks whose roles are looked up, not read from the lines.
        const std::vector<std::string> swapped = decode(swapLines(w), Feed::Blocks, 16384, {1, 0});
        ASSERT_EQ(swapped.size(), by_edge.size());
        for (std::size_t i = 0; i < by_edge.size(); ++i)
            ASSERT_EQ(swapped[i], by_edge[i]) << "swapped lines, event " << i;
    }
}

// Three frames at 1 MHz (1 ns ticks), the first with its ACK 340 ns after its rise and
// its data edges 300 ns after theirs, and one high clock phase after slot 20 stretched
// to `pause_ns`. The line delay refined over the data edges falls to about 304 ns.
Waveform pausedCapture(Tick pause_ns) {
    BisscGenConfig cfg;
    cfg.clock_hz = 1e6;
    cfg.line_delay_ns = 300;
    BisscGenerator gen(cfg);
    addPlainFrames(gen, 3, 11);
    Waveform w = gen.build();
    std::vector<Tick> rises;
    for (const Edge& e : w.edges)
        if (e.line == 0 && e.level && e.t < gen.frames()[0].end) rises.push_back(e.t);
    if (rises.size() <= 20) return w;
    const Tick ack = rises[1] + 300;
    const Tick pause_from = rises[20] + 400;  // in a high phase, after slot 20's SL change
    const Tick stretch = pause_ns - 500;      // the 500 ns high phase becomes pause_ns
    for (Edge& e : w.edges) {
        if (e.line == 1 && e.t == ack) e.t += 40;
        if (e.t > pause_from) e.t += stretch;
    }
    w.end += stretch;
    return w;
}

TEST(BisscBlocks, PauseEndsTheFrameOnlyPastTwentyMicrosecondsAndTheDelay) {
    // A clock pause ends a frame when it is longer than 20 us plus the line delay (no
    // slave timeout known yet in the first frame): 20 325 ns does, 20 290 ns does not, in
    // a run as on the general path. (The runs leave a pause over 20 us to the general
    // path, which decides.)
    for (const Tick pause : {Tick(20'325), Tick(20'290)}) {
        SCOPED_TRACE(::testing::Message() << "pause " << pause << " ns");
        const Waveform w = pausedCapture(pause);
        const std::vector<std::string> by_edge = decode(w, Feed::Reference);
        ASSERT_GE(by_edge.size(), 3u);
        EXPECT_EQ(by_edge[0].find("short_frame") != std::string::npos, pause == 20'325)
            << by_edge[0];
        EXPECT_EQ(decode(w, Feed::OneByOne), by_edge);
        EXPECT_EQ(decode(w, Feed::Blocks, 16384), by_edge);
    }
}

TEST(BisscBlocks, RunsTakeTheDataOfCleanFrames) {
    // Not only the same as the general path: in blocks, the benchmark's traffic (10 MHz,
    // 100 MS/s, 40 ns of line delay) decodes to the generator's positions, every frame.
    BisscGenConfig cfg;
    cfg.clock_hz = 10e6;
    cfg.timebase = Timebase::fromSampleRate(100'000'000);
    cfg.line_delay_ns = 40;
    BisscGenerator gen(cfg);
    addPlainFrames(gen, 50, 3);
    const Waveform w = gen.build();
    const std::vector<std::string> lines = decode(w, Feed::Blocks, 16384);
    ASSERT_EQ(lines.size(), gen.frames().size());
    for (std::size_t i = 0; i < lines.size(); ++i)
        EXPECT_NE(lines[i].find("\"position\":" + std::to_string(gen.frames()[i].spec.data)),
                  std::string::npos)
            << lines[i];
}

}  // namespace
}  // namespace busdecode::test
