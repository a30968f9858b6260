// SPI takes blocks of edges through a fast path (SpiDecoder::edges: 64 edges at a time as
// bit masks, only the sampling clock edges visited) and single edges through step(). Both
// must decode every capture to the same events, bit for bit, wherever a block or a
// chip-select change cuts the 64 edges, whatever the mode, the word width and the timing:
// data changing at the tick of a clock edge, gaps of 2^24 ticks and more, glitches.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "core/block_decoding.h"
#include "core/registry.h"
#include "sinks/event_format.h"
#include "spi_generator.h"
#include "spi_info.h"
#include "support/feed/direct_feed.h"

namespace busdecode {
namespace {

const DecoderFactory& spiFactory() {
    static const std::shared_ptr<const DecoderFactory> factory = makeSpiFactory();
    return *factory;
}

Options spiOptions(const SpiMode& mode, int bits) {
    return Options::resolve(spiFactory().info(),
                            {{"cpol", std::to_string(mode.cpol)},
                             {"cpha", std::to_string(mode.cpha)},
                             {"bits", std::to_string(bits)},
                             {"lsb_first", mode.lsb_first ? "1" : "0"},
                             {"cs_polarity", mode.cs_active_high ? "active-high" : "active-low"}});
}

// A capture (1 ns ticks) with everything drawn at random: the mode, the word width, the
// clock period (2 to 40 ticks), data changing with the shift edge or after it, words cut
// short by cs, gaps from a few ticks to over 2^24, and glitches on any line.
struct RandomCapture {
    Waveform wave;
    SpiMode mode;
    int bits = 8;
};

RandomCapture randomCapture(std::uint32_t seed) {
    std::mt19937_64 rng(seed);
    const auto pick = [&rng](int n) { return int(rng() % std::uint64_t(n)); };
    RandomCapture c;
    c.mode = SpiMode{pick(2), pick(2), pick(2) == 0, pick(3) == 0};
    const int widths[] = {1, 5, 8, 16, 32, 33, 64};
    c.bits = widths[pick(7)];
    SpiTiming tm;
    tm.period_ns = 2 * (1 + pick(20));
    tm.data_delay_ns = pick(3) == 0 ? 0 : pick(int(tm.period_ns / 2));
    tm.cs_setup_ns = pick(3) * tm.period_ns / 2;
    tm.cs_hold_ns = pick(3) * tm.period_ns / 2;
    WaveBuilder wb(Timebase{1, 1'000'000'000}, {"cs", "sclk", "mosi", "miso"},
                   SpiGenerator::idleLevels(c.mode));
    SpiGenerator gen(wb, SpiLines{0, 1, 2, 3}, c.mode, tm);
    double t = 10;
    for (int i = 0, n = 10 + pick(20); i < n; ++i) {
        std::vector<SpiGenerator::Word> words(std::size_t(1 + pick(4)));
        for (auto& w : words)
            w = {rng(), rng()};
        const int total = int(words.size()) * c.bits;
        const int cut = pick(5) == 0 ? pick(total) : -1;
        const double start = t;
        t = gen.transfer(t, words, c.bits, cut);
        // A glitch: a pulse of 1 to 3 ticks on a line, inside the transfer.
        if (pick(4) == 0) {
            const auto line = std::uint32_t(pick(4));
            const double at = std::floor(start + (t - start) * 0.01 * pick(100));
            if (at > double(wb.lastTick())) {
                const bool level = wb.level(line);
                wb.setNs(line, at, !level);
                wb.setNs(line, at + 1 + pick(3), level);
                t = std::max(t, at + 4);
            }
        }
        t += pick(6) == 0 ? double(1 << 24) + pick(1 << 20) : 1 + pick(200);
    }
    c.wave = wb.build(wb.ticksFromNs(t + 10));
    return c;
}

TEST(SpiBlocks, BlocksDecodeAsEdgeByEdgeWhateverTheTraffic) {
    for (std::uint32_t seed = 1; seed <= 120; ++seed) {
        SCOPED_TRACE(::testing::Message() << "seed " << seed);
        const RandomCapture c = randomCapture(seed);
        const Options options = spiOptions(c.mode, c.bits);
        // All four lines, then without cs (framed by count), then without miso.
        for (const std::vector<int>& lines :
             {std::vector<int>{0, 1, 2, 3}, {-1, 1, 2, 3}, {0, 1, 2, -1}}) {
            const std::vector<std::string> by_edge =
                decodeDirectly(spiFactory(), options, c.wave, lines, Feed::Reference);
            ASSERT_FALSE(by_edge.empty());
            for (const std::size_t block :
                 {std::size_t(64), std::size_t(65), std::size_t(66), std::size_t(129),
                  std::size_t(1000), std::size_t(16384)}) {
                SCOPED_TRACE(::testing::Message() << "block " << block << ", cs line " << lines[0]);
                const std::vector<std::string> by_block =
                    decodeDirectly(spiFactory(), options, c.wave, lines, Feed::Blocks, block);
                ASSERT_EQ(by_block.size(), by_edge.size());
                for (std::size_t i = 0; i < by_edge.size(); ++i)
                    ASSERT_EQ(by_block[i], by_edge[i]) << "event " << i;
            }
        }
    }
}

TEST(SpiBlocks, BlocksTakeTheGeneratorsWords) {
    // Not only the same as edge by edge: in blocks, the benchmark's traffic (32-bit words
    // back to back at 10 MHz, 100 MS/s, mode 3) gives the generator's words.
    const SpiMode mode{1, 1, false, false};
    SpiTiming tm;
    tm.period_ns = 100;
    tm.data_delay_ns = 20;
    std::mt19937_64 rng(7);
    std::vector<std::vector<SpiGenerator::Word>> transfers;
    for (int i = 0; i < 40; ++i)
        transfers.push_back({{rng() & 0xFFFFFFFFu, rng() & 0xFFFFFFFFu}});
    const Waveform w = makeSpiCapture(transfers, 32, mode, tm, 100);
    const std::vector<std::string> lines =
        decodeDirectly(spiFactory(), spiOptions(mode, 32), w, {0, 1, 2, 3}, Feed::Blocks, 16384);
    ASSERT_EQ(lines.size(), transfers.size());
    for (std::size_t i = 0; i < lines.size(); ++i) {
        EXPECT_NE(lines[i].find("\"mosi\":" + std::to_string(transfers[i][0].mosi)),
                  std::string::npos)
            << lines[i];
        EXPECT_NE(lines[i].find("\"miso\":" + std::to_string(transfers[i][0].miso)),
                  std::string::npos)
            << lines[i];
    }
}

// Events as JSON lines, for decoders fed by hand below.
struct JsonLines : EventSink {
    void onEvent(Event&& e) override {
        std::string line;
        appendEventJson(line, e, Timebase{1, 1'000'000'000});
        lines.push_back(std::move(line));
    }
    std::vector<std::string> lines;
};

TEST(SpiBlocks, EdgesNoSessionSendsDecodeAsEdgeByEdge) {
    // What a session never hands over, but edges() may be given: a level repeated, several
    // sclk edges at one tick, a second line for sclk, a line of no role, and the lines'
    // roles changed between two calls. Runs of clean clocking between them, so that the
    // fast path takes part, with data changing at a clock edge's tick (before or after it
    // in the stream) and clock edges exactly 2^24 ticks after the edge before. Lines 0-3 are cs,
    // sclk, mosi and miso; line 4 has no role, line 5 is a second sclk; the second half of the
    // calls swaps mosi and miso.
    const std::vector<int> roles_a{kSpiCs, kSpiSclk, kSpiMosi, kSpiMiso, -1, kSpiSclk};
    const std::vector<int> roles_b{kSpiCs, kSpiSclk, kSpiMiso, kSpiMosi, -1, kSpiSclk};
    for (std::uint32_t seed = 1; seed <= 60; ++seed) {
        SCOPED_TRACE(::testing::Message() << "seed " << seed);
        std::mt19937_64 rng(seed);
        const auto pick = [&rng](int n) { return int(rng() % std::uint64_t(n)); };
        std::vector<Edge> edges;
        std::vector<std::uint8_t> level{0, 1, 0, 0, 0, 1};
        Tick t = 0;
        const auto add = [&](int line, bool repeat_allowed) {
            std::uint8_t v = std::uint8_t(1 - level[std::size_t(line)]);
            if (repeat_allowed && pick(2) == 0) v = level[std::size_t(line)];
            level[std::size_t(line)] = v;
            edges.emplace_back(t, std::uint32_t(line), v);
        };
        for (int k = 0; k < 3000; ++k) {
            if (pick(40) == 0) {  // noise: any line, repeats, ticks shared
                for (int n = 1 + pick(6); n > 0; --n) {
                    add(pick(6), true);
                    t += pick(2);
                }
                continue;
            }
            // The clock, now and then exactly 2^24 ticks after the edge before (the same
            // low 24 bits, which the masks compare).
            t += pick(150) == 0 ? Tick(1) << 24 : 1 + pick(4);
            if (pick(4) == 0) add(2 + pick(2), false);  // data at the clock edge's tick
            add(1, false);
            if (pick(2) == 0) {
                t += pick(2);  // data with the clock edge, or a tick later
                add(2 + pick(2), false);
                if (pick(3) == 0) add(pick(2) == 0 ? 2 : 3, false);
            }
            if (pick(200) == 0) add(0, false);  // cs
        }
        const Options options = spiOptions(SpiMode{pick(2), pick(2), pick(2) == 0, false}, 8);
        DecoderContext ctx;
        ctx.timebase = Timebase{1, 1'000'000'000};
        ctx.initial_levels = {0, 1, 0, 0};

        JsonLines one_by_one, in_blocks;
        std::unique_ptr<Decoder> a = spiFactory().create(options);
        std::unique_ptr<Decoder> b = spiFactory().create(options);
        ctx.sink = &one_by_one;
        a->start(ctx);
        ctx.sink = &in_blocks;
        b->start(ctx);
        const std::size_t half = edges.size() / 2;
        for (std::size_t i = 0; i < edges.size(); ++i) {
            const std::vector<int>& roles = i < half ? roles_a : roles_b;
            const int role = roles[edges[i].line];
            if (role >= 0) a->edge(edges[i].t, role, edges[i].level != 0);
        }
        for (std::size_t i = 0; i < edges.size();) {
            const std::size_t end = std::min(
                {edges.size(), i + 1 + std::size_t(pick(400)), i < half ? half : edges.size()});
            fastPathOf(*b)->edges(edges.data() + i, edges.data() + end,
                                  (i < half ? roles_a : roles_b).data());
            i = end;
        }
        a->finish(t + 100);
        b->finish(t + 100);
        ASSERT_GT(one_by_one.lines.size(), 50u);
        ASSERT_EQ(in_blocks.lines.size(), one_by_one.lines.size());
        for (std::size_t i = 0; i < one_by_one.lines.size(); ++i)
            ASSERT_EQ(in_blocks.lines[i], one_by_one.lines[i]) << "event " << i;
    }
}

}  // namespace
}  // namespace busdecode
