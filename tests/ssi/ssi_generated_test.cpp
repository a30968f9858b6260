// The decoder on generated captures with known truth: word widths, Gray, multiple
// transmission, tm, clock rates, jitter, cable delay, glitches, truncation, re-reads.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include <fmt/format.h>

#include "core/bit_word.h"
#include "core/gray.h"
#include "core/session.h"
#include "sinks/event_format.h"
#include "ssi_generator.h"
#include "ssi_test_util.h"
#include "support/decode_events.h"

using namespace busdecode;
using namespace busdecode::ssitest;

namespace {

std::vector<SsiGenFrame> randomFrames(int n, int width, std::uint64_t seed,
                                      double pause_ns = 50000) {
    std::mt19937_64 rng(seed);
    std::vector<SsiGenFrame> out;
    for (int i = 0; i < n; ++i) {
        SsiGenFrame f;
        f.word = lowBits(rng(), width);
        f.pause_ns = pause_ns;
        out.push_back(f);
    }
    return out;
}

std::map<std::string, std::string> opts(int bits, int st, int mt, bool gray) {
    return {{"bits", std::to_string(bits)},
            {"st_bits", std::to_string(st)},
            {"mt_bits", std::to_string(mt)},
            {"gray", gray ? "1" : "0"}};
}

}  // namespace

TEST(SsiGenerated, WidthsTenToFortyGrayAndBinary) {
    for (int width = 10; width <= 40; ++width) {
        for (bool gray : {false, true}) {
            SCOPED_TRACE(fmt::format("width {} gray {}", width, gray));
            SsiGenConfig cfg;
            cfg.data_bits = width;
            cfg.seed = std::uint64_t(width * 2 + gray);
            const auto frames = randomFrames(6, width, cfg.seed);
            const auto g = generateSsi(cfg, frames);
            const int st = std::min(width, 16), mt = std::min(width - st, 12);
            const auto ev = decodeFrames(g.wave, opts(width, st, mt, gray));
            expectTruth(ev, g);
            for (std::size_t i = 0; i < ev.size() && i < frames.size(); ++i) {
                std::uint64_t pos = lowBits(frames[i].word, st + mt);
                if (gray) pos = grayToBinary(pos);
                EXPECT_EQ(u64(ev[i], "position"), pos);
                EXPECT_EQ(u64(ev[i], "st"), lowBits(pos, st));
                EXPECT_EQ(u64(ev[i], "mt"), lowBits(pos >> st, mt));
                EXPECT_NEAR(asDouble(*ev[i].get("angle")),
                            360.0 * double(lowBits(pos, st)) / std::ldexp(1.0, st), 1e-9);
                if (i == 0) {
                    EXPECT_TRUE(isNull(*ev[i].get("tp_ns")));
                } else {
                    EXPECT_EQ(i64(ev[i], "tp_ns"), 50000);
                }
            }
        }
    }
}

TEST(SsiGenerated, RingShiftOneToFourRepeats) {
    for (int repeats = 1; repeats <= 4; ++repeats) {
        for (bool corrupt : {false, true}) {
            if (corrupt && repeats == 1) continue;
            SCOPED_TRACE(fmt::format("repeats {} corrupt {}", repeats, corrupt));
            SsiGenConfig cfg;
            cfg.data_bits = 25;
            cfg.seed = std::uint64_t(repeats * 10 + corrupt);
            auto frames = randomFrames(5, 25, cfg.seed);
            for (std::size_t i = 0; i < frames.size(); ++i) {
                frames[i].repeats = repeats;
                if (corrupt && i % 2 == 1) frames[i].flips = {{repeats - 1, int(i) * 3}, {1, 24}};
            }
            const auto g = generateSsi(cfg, frames);
            int mismatching = 0;
            for (const auto& t : g.frames)
                mismatching += !t.repeat_match;
            EXPECT_EQ(mismatching, corrupt ? 2 : 0);  // the truth itself is not trivial
            expectTruth(decodeFrames(g.wave, opts(25, 16, 9, true)), g);
        }
    }
}

TEST(SsiGenerated, RingGapAndPartialRepeat) {
    SsiGenConfig cfg;
    cfg.data_bits = 13;
    cfg.ring_gap = 3;
    auto frames = randomFrames(4, 13, 7);
    frames[0].repeats = 3;
    frames[1].clocks = 13 + 1 + 3 + 5;  // stops 5 bits into the repeat
    frames[2].repeats = 2;
    frames[2].flips = {{1, 0}};
    const auto g = generateSsi(cfg, frames);
    EXPECT_EQ(g.frames[1].partial_bits, 5);
    // The partial repeat ends on whatever bit was being sent: tm may be unmeasurable.
    expectTruth(decodeFrames(g.wave, {{"bits", "13"}, {"st_bits", "13"}, {"ring_gap", "3"}}), g,
                {"tm_missing"});
}

TEST(SsiGenerated, MonoflopTimeFifteenToTwentyFive) {
    for (double tm_us : {15.0, 17.5, 20.0, 22.5, 25.0}) {
        SCOPED_TRACE(fmt::format("tm {} us", tm_us));
        SsiGenConfig cfg;
        cfg.tm_ns = tm_us * 1000;
        const auto g = generateSsi(cfg, randomFrames(5, 25, 3));
        const auto ev = decodeFrames(g.wave, opts(25, 16, 0, false));
        expectTruth(ev, g);
        for (const auto& e : ev)
            EXPECT_NEAR(asDouble(*e.get("tm_ns")), tm_us * 1000, 1);
    }
    // Outside the window around tm_us (default tm_us/2 .. 2*tm_us).
    SsiGenConfig cfg;
    cfg.tm_ns = 5000;
    auto g = generateSsi(cfg, randomFrames(3, 25, 4));
    auto ev = decodeFrames(g.wave, opts(25, 16, 0, false));
    expectTruth(ev, g, {"timeout_short"});
    for (const auto& e : ev)
        EXPECT_TRUE(e.hasError("timeout_short"));
    cfg.tm_ns = 30000;
    g = generateSsi(cfg, randomFrames(3, 25, 4, 100000));
    ev = decodeFrames(g.wave, {{"tm_us", "20"}, {"tm_max_us", "25"}});
    expectTruth(ev, g, {"timeout_long"});
    for (const auto& e : ev)
        EXPECT_TRUE(e.hasError("timeout_long"));
}

TEST(SsiGenerated, ClockHundredKilohertzToTwoMegahertz) {
    for (double hz : {100e3, 250e3, 500e3, 1e6, 1.5e6, 2e6}) {
        SCOPED_TRACE(fmt::format("clock {} Hz", hz));
        SsiGenConfig cfg;
        cfg.clock_hz = hz;
        cfg.sample_rate_hz = 100'000'000;  // 10 ns ticks, as a logic analyser would
        cfg.seed = std::uint64_t(hz);
        const auto g = generateSsi(cfg, randomFrames(5, 25, cfg.seed, 60000));
        const auto ev = decodeFrames(g.wave, opts(25, 16, 9, true));
        expectTruth(ev, g);
    }
    for (double hz : {20e3, 4e6}) {
        SsiGenConfig cfg;
        cfg.clock_hz = hz;
        cfg.tm_ns = 60000;  // an encoder for slow clocks
        const auto g = generateSsi(cfg, randomFrames(3, 25, 5, 200000));
        const auto ev = decodeFrames(g.wave, {{"tm_us", "60"}});
        expectTruth(ev, g, {"clock_range"});
        for (const auto& e : ev)
            EXPECT_TRUE(e.hasError("clock_range")) << describe(e);
    }
}

TEST(SsiGenerated, ClockJitter) {
    SsiGenConfig cfg;
    cfg.clock_hz = 1e6;
    cfg.jitter_ns = 120;
    cfg.seed = 99;
    auto frames = randomFrames(40, 25, 99);
    for (std::size_t i = 0; i < frames.size(); i += 3)
        frames[i].repeats = 2;
    const auto g = generateSsi(cfg, frames);
    expectTruth(decodeFrames(g.wave, opts(25, 16, 9, true)), g);
}

TEST(SsiGenerated, CableDelay) {
    SsiGenConfig cfg;
    cfg.clock_hz = 1e6;
    cfg.delay_ns = 300;  // less than half a period: falling-edge sampling still works
    auto g = generateSsi(cfg, randomFrames(6, 25, 11));
    auto ev = decodeFrames(g.wave, opts(25, 16, 0, false));
    expectTruth(ev, g);
    for (const auto& e : ev)
        EXPECT_EQ(i64(e, "delay_ns"), 300);

    cfg.delay_ns = 700;  // data changes after the falling edge: bits would be misread
    g = generateSsi(cfg, randomFrames(6, 25, 12));
    ev = decodeFrames(g.wave, opts(25, 16, 0, false));
    ASSERT_EQ(ev.size(), g.frames.size());
    int wrong = 0;
    for (std::size_t i = 0; i < ev.size(); ++i) {
        EXPECT_TRUE(ev[i].hasError("late_data")) << describe(ev[i]);
        wrong += u64(ev[i], "raw") != g.frames[i].raw;
    }
    EXPECT_GT(wrong, 0);
    ev = decodeFrames(g.wave, {{"bits", "25"}, {"delay_ns", "auto"}});
    expectTruth(ev, g);
    for (const auto& e : ev)
        EXPECT_EQ(i64(e, "delay_ns"), 700);
    ev = decodeFrames(g.wave, {{"bits", "25"}, {"delay_ns", "650"}});
    expectTruth(ev, g);
}

TEST(SsiGenerated, CableDelayBeyondOnePeriod) {
    // 1200 ns at 1 MHz: data edges 200 ns after the rising edge after the one that launched
    // them. The first frame shows the whole period (its LSB 1 falls to the end low 1200 ns
    // after the last clock), the later ones, whatever their bits, keep it.
    SsiGenConfig cfg;
    cfg.delay_ns = 1200;
    auto frames = randomFrames(6, 25, 13);
    frames[0].word = 0x0123457;
    frames[1].word = 0x1ABCDEE;  // MSB 1, LSB 0: its edges alone allow 200 ns too
    const auto g = generateSsi(cfg, frames);
    auto ev = decodeFrames(g.wave, {{"bits", "25"}, {"delay_ns", "auto"}});
    expectTruth(ev, g);
    for (const auto& e : ev)
        EXPECT_EQ(i64(e, "delay_ns"), 1200);
    ev = decodeFrames(g.wave, {{"bits", "25"}, {"delay_ns", "1200"}});
    expectTruth(ev, g);
    ev = decodeFrames(g.wave, {{"bits", "25"}});  // sampled at the falling edge: too early
    ASSERT_EQ(ev.size(), g.frames.size());
    for (const auto& e : ev) {
        EXPECT_TRUE(e.hasError("late_data")) << describe(e);
        EXPECT_EQ(i64(e, "delay_ns"), 1200);
    }
}

TEST(SsiGenerated, GlitchesRemovedByGlitchFilter) {
    SsiGenConfig cfg;
    cfg.clock_hz = 500e3;  // 2 us period
    const auto frames = randomFrames(4, 25, 21, 60000);
    // Frame k starts at 60 us + k * (51 us of clocks + 60 us pause); glitches well inside
    // clock phases.
    const double f1 = 60000, f2 = 60000 + 2 * (51000 + 60000);
    cfg.glitches = {{0, f1 + 2000 * 5 + 1500, 30},    // clock high phase of pulse 6
                    {0, f1 + 2000 * 9 + 500, 25},     // clock low phase of pulse 10
                    {1, f2 + 2000 * 12 + 1200, 40}};  // data, between two samples
    const auto g = generateSsi(cfg, frames);
    auto opt = opts(25, 16, 0, false);
    opt["glitch_ns"] = "60";
    const auto ev = decodeFrames(g.wave, opt);
    expectTruth(ev, g, {"glitch"});
    ASSERT_EQ(ev.size(), 4u);
    EXPECT_TRUE(ev[0].hasError("glitch"));
    EXPECT_EQ(i64(ev[0], "glitches"), 2);
    EXPECT_FALSE(ev[1].hasError("glitch"));
    EXPECT_TRUE(ev[2].hasError("glitch"));
    EXPECT_FALSE(ev[3].hasError("glitch"));

    // Without the filter: the data glitch misses the samples (word intact, flagged); the
    // clock glitches add bits (frame broken, flagged).
    const auto raw = decodeFrames(g.wave, opts(25, 16, 0, false));
    ASSERT_EQ(raw.size(), 4u);
    EXPECT_TRUE(raw[0].hasError("glitch"));
    EXPECT_NE(u64(raw[0], "raw"), g.frames[0].raw);
    EXPECT_TRUE(raw[2].hasError("glitch"));
    EXPECT_EQ(u64(raw[2], "raw"), g.frames[2].raw);
    EXPECT_TRUE(raw[1].errors.empty());
}

TEST(SsiGenerated, TruncatedFrames) {
    SsiGenConfig cfg;
    auto frames = randomFrames(4, 25, 31);
    frames[1].clocks = 10;  // the master stops after 9 data bits
    const auto g = generateSsi(cfg, frames);
    ASSERT_TRUE(g.frames[1].short_frame);
    EXPECT_EQ(g.frames[1].bits, 9);
    EXPECT_EQ(g.frames[1].raw, frames[1].word >> 16);
    expectTruth(decodeFrames(g.wave, opts(25, 16, 0, false)), g);

    // The capture ends in the middle of the last frame (clock low, and clock high).
    for (double into : {12300.0, 12800.0}) {
        SsiGenConfig cut = cfg;
        cut.cut_ns = 3 * 50000 + 2 * 26000 + 50000 + into;
        const auto gc = generateSsi(cut, frames);
        ASSERT_EQ(gc.frames.size(), 4u);
        EXPECT_TRUE(gc.frames[3].short_frame);
        EXPECT_FALSE(gc.frames[3].tm_ns.has_value());
        expectTruth(decodeFrames(gc.wave, opts(25, 16, 0, false)), gc);
    }
    // ... and in the monoflop time after a complete word: tm unknown, no error.
    SsiGenConfig tail = cfg;
    tail.tail_ns = -15000;
    const auto gt = generateSsi(tail, randomFrames(2, 25, 32));
    EXPECT_FALSE(gt.frames[1].tm_ns.has_value());
    expectTruth(decodeFrames(gt.wave, opts(25, 16, 0, false)), gt);
}

TEST(SsiGenerated, RereadWhileDataLow) {
    SsiGenConfig cfg;
    auto frames = randomFrames(6, 25, 41);
    frames[1].pause_ns = 8000;  // within tm: the encoder re-sends the latched word
    frames[2].pause_ns = 5000;
    frames[4].pause_ns = 12000;
    frames[4].repeats = 2;
    const auto g = generateSsi(cfg, frames);
    ASSERT_TRUE(g.frames[1].reread);
    ASSERT_TRUE(g.frames[2].reread);
    EXPECT_EQ(g.frames[2].raw, frames[0].word);
    const auto ev = decodeFrames(g.wave, opts(25, 16, 0, false));
    expectTruth(ev, g);
    EXPECT_EQ(i64(ev[1], "tp_ns"), 8000);
}

TEST(SsiGenerated, RereadOfAChangedWordIsAMismatch) {
    // A faulty encoder that updates its word between two reads within tm.
    SsiGenConfig cfg;
    cfg.data_bits = 13;
    std::vector<SsiGenFrame> frames(3);
    frames[0].word = 0x1234;
    frames[1].word = 0x1236;
    frames[1].pause_ns = 8000;
    frames[1].relatch = true;
    frames[2].word = 0x0F0F;
    const auto g = generateSsi(cfg, frames);
    ASSERT_TRUE(g.frames[1].reread);
    EXPECT_FALSE(g.frames[1].repeat_match);
    EXPECT_EQ(g.frames[1].diff_bits, (std::vector<std::int64_t>{1}));
    const auto ev = decodeFrames(g.wave, {{"bits", "13"}, {"st_bits", "13"}});
    expectTruth(ev, g);
    ASSERT_EQ(ev.size(), 3u);
    EXPECT_TRUE(isNull(*ev[0].get("tm_ns")));
    EXPECT_TRUE(ev[1].hasError("repeat_mismatch"));
}

TEST(SsiGenerated, NotReadyWhenDataLowAtStart) {
    SsiGenConfig cfg;
    cfg.data_bits = 13;
    auto g = generateSsi(cfg, {SsiGenFrame{0x0FFF, 0, 1, 50000, {}}});
    // The data line held low from the start until the MSB is driven.
    Waveform w = g.wave;
    w.initial[1] = 0;
    const auto ev = decodeFrames(w, {{"bits", "13"}, {"st_bits", "13"}});
    ASSERT_EQ(ev.size(), 1u);
    EXPECT_TRUE(ev[0].hasError("not_ready")) << describe(ev[0]);
    EXPECT_FALSE(flag(ev[0], "reread"));
}

TEST(SsiGenerated, PositalLeadBitOnTheWire) {
    SsiGenConfig cfg;
    cfg.data_bits = 24;
    cfg.lead = true;
    const auto g = generateSsi(
        cfg, {SsiGenFrame{0x0014ED, 0, 1, 30000, {}}, SsiGenFrame{0x0014ED, 0, 2, 50000, {}}});
    EXPECT_EQ(g.frames[0].raw, 0x010014EDu);
    const auto ev =
        decodeFrames(g.wave, {{"bits", "25"}, {"lead", "1"}, {"mt_bits", "12"}, {"st_bits", "12"}});
    expectTruth(ev, g);
    ASSERT_EQ(ev.size(), 2u);
    EXPECT_EQ(u64(ev[0], "mt"), 1u);
    EXPECT_EQ(u64(ev[0], "st"), 0x4EDu);
    EXPECT_NEAR(asDouble(*ev[0].get("angle")), 110.83, 0.005);
    EXPECT_EQ(i64(ev[1], "repeats"), 2);
    EXPECT_NE(ev[0].summary.find("mt=0x1 st=0x4ED angle=110.83"), std::string::npos)
        << ev[0].summary;
}

TEST(SsiGenerated, Tmc8100LayoutStatusBits) {
    // 25-bit datagram, 26 clocks at 1 MHz, bit 23 "outside the measuring range", bit 22
    // "lower signal quality", 16-bit Gray position.
    SsiGenConfig cfg;
    std::vector<SsiGenFrame> frames;
    const std::uint64_t positions[] = {0x1234, 0xFFFF, 0x8000};
    const std::uint64_t flags[] = {0, 1u << 23, 1u << 22};
    for (int i = 0; i < 3; ++i)
        frames.push_back({flags[i] | binaryToGray(positions[i]), 0, 1, 40000, {}});
    const auto g = generateSsi(cfg, frames);
    const auto ev = decodeFrames(g.wave, {{"bits", "25"},
                                          {"st_bits", "16"},
                                          {"gray", "1"},
                                          {"status_bits", "out_of_range@23,low_quality@22"}});
    expectTruth(ev, g);
    ASSERT_EQ(ev.size(), 3u);
    for (int i = 0; i < 3; ++i) {
        EXPECT_EQ(u64(ev[i], "st"), positions[i]);
        EXPECT_EQ(flag(ev[i], "out_of_range"), i == 1);
        EXPECT_EQ(flag(ev[i], "low_quality"), i == 2);
    }
    EXPECT_NE(ev[1].summary.find("out_of_range"), std::string::npos);
    EXPECT_EQ(ev[0].get("out_of_range")->index(), Value(false).index());
}

TEST(SsiGenerated, ParityBitAfterLsb) {
    SsiGenConfig cfg;
    cfg.data_bits = 14;
    std::vector<SsiGenFrame> frames;
    for (std::uint64_t v : {0x1234ull, 0x0FFFull, 0x0001ull}) {
        const std::uint64_t par = __builtin_popcountll(v) & 1;  // even parity
        frames.push_back({(v << 1) | par, 0, 1, 40000, {}});
    }
    frames.push_back({(0x0003ull << 1) | 1, 0, 1, 40000, {}});  // wrong parity
    const auto g = generateSsi(cfg, frames);
    const auto ev = decodeFrames(g.wave, {{"bits", "14"}, {"st_bits", "13"}, {"parity", "even"}});
    expectTruth(ev, g, {"parity"});
    ASSERT_EQ(ev.size(), 4u);
    EXPECT_EQ(u64(ev[0], "st"), 0x1234u);
    EXPECT_EQ(u64(ev[1], "st"), 0x0FFFu);
    for (int i = 0; i < 3; ++i)
        EXPECT_TRUE(flag(ev[i], "parity_ok"));
    EXPECT_FALSE(flag(ev[3], "parity_ok"));
    EXPECT_TRUE(ev[3].hasError("parity"));
}

namespace {

// Five 25-bit frames with tm = 18 us, from `seed`.
Waveform fiveFramesTm18(unsigned seed) {
    SsiGenConfig cfg;
    cfg.tm_ns = 18000;
    return generateSsi(cfg, randomFrames(5, 25, seed)).wave;
}

DecoderRequest ssi25() {
    registerSsi();
    DecoderRequest r;
    r.proto = "ssi";
    r.options = {{"bits", "25"}};
    return r;
}

}  // namespace

TEST(SsiGenerated, SummaryEventHasTmStatistics) {
    const auto all = decodeWaveform(fiveFramesTm18(51), {ssi25()});
    ASSERT_FALSE(all.empty());
    const Event& s = all.back();
    ASSERT_EQ(s.type, "summary");
    EXPECT_EQ(i64(s, "frames"), 5);
    EXPECT_NEAR(asDouble(*s.get("tm_median_ns")), 18000, 1);
    EXPECT_NEAR(asDouble(*s.get("clock_hz_max")), 1e6, 1e4);
    EXPECT_EQ(i64(s, "repeat_mismatches"), 0);
    for (std::size_t i = 1; i < all.size(); ++i)
        EXPECT_LE(all[i - 1].start, all[i].start);
}

TEST(SsiGenerated, JsonlOutputGetsTheFieldsWithoutSummary) {
    // A sink that reads no summaries (jsonl, Python) gets the same frames, fields and
    // errors, without the summary text output prints.
    const Waveform w = fiveFramesTm18(52);
    const auto both = decodeWaveform(w, {ssi25()});
    const auto json = test::decodeForFields(w, {ssi25()});
    ASSERT_EQ(json.size(), both.size());
    ASSERT_EQ(json.size(), 6u);  // five frames and the summary event
    for (std::size_t i = 0; i < 5; ++i) {
        EXPECT_EQ(json[i].summary, "");
        EXPECT_NE(both[i].summary.find("tm=18.0us"), std::string::npos) << both[i].summary;
        EXPECT_EQ(eventToJson(json[i], w.timebase), eventToJson(both[i], w.timebase));
    }
}

TEST(SsiGenerated, RisingEdgeSamplerRejectsThePauseBit) {
    // TR's rising-edge master: the first rising-edge sample is the pause 1 (dropped with
    // lead=0), then MSB..LSB; the data must lag the clock for this to work at all.
    SsiGenConfig cfg;
    cfg.delay_ns = 150;
    cfg.jitter_ns = 30;
    auto frames = randomFrames(8, 25, 61);
    frames[3].repeats = 3;
    const auto g = generateSsi(cfg, frames);
    auto o = opts(25, 16, 9, false);
    o["sample_edge"] = "rising";
    expectTruth(decodeFrames(g.wave, o), g);
    o["delay_ns"] = "auto";
    const auto ev = decodeFrames(g.wave, o);
    expectTruth(ev, g);
    for (const auto& e : ev)
        EXPECT_EQ(i64(e, "delay_ns"), 150);
    // A fixed offset beyond the data change reads the next bit and says so.
    o["delay_ns"] = "200";
    const auto wrong = decodeFrames(g.wave, o);
    ASSERT_EQ(wrong.size(), g.frames.size());
    for (const auto& e : wrong)
        EXPECT_TRUE(e.hasError("sample_late")) << describe(e);
}

TEST(SsiGenerated, RandomEdgesNeverBreakTheDecoder) {
    // Noise on both lines: frames of any shape, but every one well-formed and in order.
    std::mt19937_64 rng(77);
    for (int round = 0; round < 20; ++round) {
        WaveBuilder wb(Timebase{1, 1'000'000'000}, {"clk", "data"}, {1, 1});
        Tick t = 0;
        bool lv[2] = {true, true};
        for (int i = 0; i < 3000; ++i) {
            t += Tick(1 + rng() % (round % 2 ? 3000 : 400));
            const int line = int(rng() % 3 == 0);
            lv[line] = !lv[line];
            wb.set(line, t, lv[line]);
        }
        std::map<std::string, std::string> o = opts(25, 16, 9, round % 3 == 0);
        if (round % 4 == 1) o["delay_ns"] = "auto";
        if (round % 4 == 2) o["sample_edge"] = "rising";
        if (round % 5 == 3) o["glitch_ns"] = "30";
        const auto ev = decodeFrames(wb.build(t + 100000), o);
        EXPECT_FALSE(ev.empty());
        for (std::size_t i = 0; i < ev.size(); ++i) {
            EXPECT_LE(ev[i].start, ev[i].end);
            if (i) {
                EXPECT_LT(ev[i - 1].end, ev[i].start);
            }
            for (const char* key : {"raw", "bits", "position", "st", "mt", "angle", "repeats",
                                    "repeat_match", "clock_hz", "tm_ns"})
                EXPECT_TRUE(ev[i].has(key)) << key;
        }
    }
}

TEST(SsiGenerated, SummaryTextOfV32) {
    // docs/protocols.md V32: 25-bit Gray, MT 0xABC, ST 0x1234 (13 bits) -> raw 0x1FC5B2E.
    SsiGenConfig cfg;
    const auto g = generateSsi(cfg, {SsiGenFrame{binaryToGray(0x1579234), 0, 1, 30000, {}}});
    const auto ev = decodeFrames(g.wave, opts(25, 13, 12, true));
    ASSERT_EQ(ev.size(), 1u);
    EXPECT_EQ(ev[0].summary,
              "raw=0x1FC5B2E pos=0x1579234 mt=0xABC st=0x1234 angle=204.79 repeats=1 "
              "clk=1.00MHz tm=20.0us");
}

TEST(SsiGenerated, DataStuckLowOrHighAfterTheWord) {
    SsiGenConfig cfg;
    cfg.tail_ns = 1'000'000;
    auto g = generateSsi(cfg, randomFrames(2, 25, 71));
    // Drop the last data edge (the monoflop's return high): data stays low to the end.
    Waveform low = g.wave;
    for (auto it = low.edges.rbegin(); it != low.edges.rend(); ++it)
        if (it->line == 1) {
            low.edges.erase(std::next(it).base());
            break;
        }
    auto ev = decodeFrames(low, opts(25, 16, 0, false));
    ASSERT_EQ(ev.size(), 2u);
    EXPECT_FALSE(ev[0].hasError("timeout_long"));
    EXPECT_TRUE(isNull(*ev[1].get("tm_ns")));
    EXPECT_TRUE(ev[1].hasError("timeout_long")) << describe(ev[1]);

    // A broken data line stays high: all ones and no low level after the word.
    Waveform high = g.wave;
    std::erase_if(high.edges, [](const Edge& e) { return e.line == 1; });
    ev = decodeFrames(high, opts(25, 16, 0, false));
    ASSERT_EQ(ev.size(), 2u);
    for (const auto& e : ev) {
        EXPECT_EQ(u64(e, "raw"), 0x1FFFFFFu);
        EXPECT_TRUE(e.hasError("tm_missing")) << describe(e);
    }
}

TEST(SsiGenerated, DataStuckLowBetweenPollsIsNotReadyNotReread) {
    // Polled every 80 us with tm 20 us (tm_max 40 us): once the data line breaks low, no
    // burst starts within tm_max of the last one, so none is a re-read of a latched word.
    SsiGenConfig cfg;
    cfg.data_bits = 13;
    cfg.clock_hz = 500e3;
    cfg.tail_ns = 1'000'000;  // the last frame's data stays low past 10 * tm_max
    const auto g = generateSsi(cfg, randomFrames(6, 13, 81, 80000));
    const Tick broken = g.frames[1].end + 40000;
    ASSERT_LT(broken, g.frames[2].start);
    Waveform w = g.wave;
    std::erase_if(w.edges, [&](const Edge& e) { return e.line == 1 && e.t >= broken; });
    w.edges.insert(
        std::find_if(w.edges.begin(), w.edges.end(), [&](const Edge& e) { return e.t >= broken; }),
        Edge{broken, 1, 0});
    const auto ev = decodeFrames(w, {{"bits", "13"}, {"st_bits", "13"}});
    ASSERT_EQ(ev.size(), 6u);
    for (std::size_t i = 2; i < ev.size(); ++i) {
        EXPECT_TRUE(ev[i].hasError("not_ready")) << i << ": " << describe(ev[i]);
        EXPECT_FALSE(flag(ev[i], "reread")) << i << ": " << describe(ev[i]);
        EXPECT_EQ(u64(ev[i], "raw"), 0u);
        EXPECT_TRUE(ev[i].hasError("timeout_long")) << i << ": " << describe(ev[i]);
    }
    expectTruth(decodeFrames(g.wave, {{"bits", "13"}, {"st_bits", "13"}}), g);
}
