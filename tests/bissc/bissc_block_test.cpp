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
#include "bissc_test_util.h"
#include "core/direct_feed.h"

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
// a line is not its role and the runs look the role up (DecoderContext::lines_are_roles).
Waveform swapLines(Waveform w) {
    std::swap(w.names[0], w.names[1]);
    std::swap(w.initial[0], w.initial[1]);
    for (Edge& e : w.edges)
        e = Edge(e.t, 1u - std::uint32_t(e.line), std::uint8_t(e.level));
    return w;
}

// A capture of `frames` frames with everything the generator can vary drawn at random:
// the sample rate, line delays of up to several bit times, jitter, busy clocks, clocks
// past the stop bit, a slave that takes those for a new request, Hold-CDM, corrupted
// CRCs, frames cut short, and glitches on both lines.
Waveform randomCapture(std::uint32_t seed, int frames) {
    std::mt19937_64 rng(seed);
    const auto pick = [&rng](int n) { return int(rng() % std::uint64_t(n)); };
    BisscGenConfig cfg;
    const double clocks[] = {1e6, 2.5e6, 10e6};
    cfg.clock_hz = clocks[pick(3)];
    const double period_ns = 1e9 / cfg.clock_hz;
    cfg.bits = 26;
    cfg.line_delay_ns = period_ns * 0.1 * pick(40);  // 0 to 3.9 bit times
    const std::int64_t rates[] = {0, 24'000'000, 100'000'000};
    if (const std::int64_t rate = rates[pick(3)]) {
        cfg.timebase = Timebase::fromSampleRate(rate);
    } else {
        cfg.jitter_ns = period_ns * 0.01 * pick(6);  // 0 to 5 % of a period
    }
    cfg.hold_cdm = pick(4) == 0;
    if (pick(4) == 0) cfg.ready_after_stop_ns = period_ns * pick(3);
    cfg.timeout_ns = 15000 + 2 * period_ns;
    cfg.seed = seed;
    BisscGenerator gen(cfg);
    for (int i = 0; i < frames; ++i) {
        BisscFrameSpec f;
        f.data = rng() & ((1ull << 26) - 1);
        f.ne = int(pick(5) != 0);
        f.nw = int(pick(4) != 0);
        f.cds = pick(2);
        f.cdm = pick(2);
        f.proc_cycles = pick(6);
        f.extra_clocks = pick(3) == 0 ? pick(5) : 0;
        f.corrupt_crc = pick(7) == 0;
        if (pick(9) == 0) f.truncate_after = 2 + pick(38);
        const double start = gen.nowNs();
        gen.addFrame(f);
        if (pick(6) == 0)
            gen.addGlitch(pick(2), start + (gen.nowNs() - start) * 0.01 * pick(100), 5);
    }
    return gen.build();
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
