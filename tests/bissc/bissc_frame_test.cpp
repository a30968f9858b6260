// BiSS-C frames: the published frame vectors (docs/protocols.md §4.2) built slot by slot,
// then generated captures across clock rates, widths, line delays and processing times.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "bissc_generator.h"
#include "bissc_test_util.h"
#include "core/bit_word.h"

using namespace busdecode;
using namespace busdecode::test;

namespace {

// A frame from its slot string (SL level driven after each MA rising edge, slot 0 = LAT),
// independent of the generator: MA at period_ns, SL answering delay_ns after each rise.
Waveform fromSlots(const std::string& slots, double period_ns, double delay_ns, bool cdm = false) {
    WaveBuilder b(Timebase{1, 1'000'000'000}, {"MA", "SLO"}, {1, 1});
    const double t0 = 2000;
    double last = t0;
    for (std::size_t k = 0; k < slots.size(); ++k) {
        const double r = t0 + period_ns / 2 + double(k) * period_ns;
        b.setNs(0, r - period_ns / 2, false);
        b.setNs(0, r, true);
        if (k > 0) b.setNs(1, r + delay_ns, slots[k] == '1');
        last = r;
    }
    if (cdm) b.setNs(0, last + period_ns / 2, false);
    b.setNs(1, last + delay_ns + 20000, true);
    if (cdm) b.setNs(0, last + delay_ns + 21000, true);
    return b.build(b.ticksFromNs(last + 40000));
}

std::string strip(std::string s) {
    s.erase(std::remove(s.begin(), s.end(), ' '), s.end());
    return s;
}

}  // namespace

TEST(BisscFrameVectors, V10_13bit_nW_active) {
    const std::string slots = strip("1 0 1 0 0101001011010 1 0 101011 0");
    ASSERT_EQ(slots, "10100101001011010101010110");
    for (double delay : {0.0, 80.0, 2600.0}) {  // 2.6 us = 2.6 bit times at 1 MHz
        auto frames = ofType(decodeBissc(fromSlots(slots, 1000, delay), {{"bits", "13"}}), "frame");
        ASSERT_EQ(frames.size(), 1u) << delay;
        const Event& f = frames[0];
        EXPECT_EQ(intField(f, "position"), 0x0A5A);
        EXPECT_EQ(intField(f, "nE"), 1);
        EXPECT_EQ(intField(f, "nW"), 0);
        EXPECT_EQ(intField(f, "crc_rx"), 0x2B);
        EXPECT_TRUE(std::get<bool>(*f.get("crc_ok")));
        EXPECT_EQ(intField(f, "cds"), 0);
        EXPECT_EQ(intField(f, "cdm"), 0);
        EXPECT_EQ(intField(f, "proc_cycles"), 0);
        EXPECT_EQ(intField(f, "line_delay_ns"), std::llround(delay));
        EXPECT_EQ(intField(f, "extra_clocks"), 0);
        EXPECT_EQ(intField(f, "clocks"), 26);
        EXPECT_NEAR(std::get<double>(*f.get("clock_hz")), 1e6, 1);
        EXPECT_EQ(f.errors, std::vector<std::string>{"warning_bit"});
    }
}

TEST(BisscFrameVectors, V11_24bit_four_ack_clocks) {
    const std::string slots = strip("1 0000 1 0 000100100011010001010110 11 110101 0");
    auto frames = ofType(decodeBissc(fromSlots(slots, 400, 150, true), {{"bits", "24"}}), "frame");
    ASSERT_EQ(frames.size(), 1u);
    const Event& f = frames[0];
    EXPECT_EQ(intField(f, "position"), 0x123456);
    EXPECT_EQ(intField(f, "crc_rx"), 0x35);
    EXPECT_TRUE(std::get<bool>(*f.get("crc_ok")));
    EXPECT_EQ(intField(f, "proc_cycles"), 3);
    EXPECT_EQ(intField(f, "cdm"), 1);
    EXPECT_EQ(intField(f, "line_delay_ns"), 150);
    EXPECT_TRUE(f.errors.empty());
}

TEST(BisscFrameVectors, V12_AN18_capture_data) {
    // AN18 Fig. 10: 24-bit 0x05AC53, nE = nW = 0, CRC 101111.
    const std::string slots =
        "1"
        "0"
        "1"
        "0" +
        strip("00000101101011000101001100101111") + "0";
    auto frames = ofType(decodeBissc(fromSlots(slots, 500, 0), {{"bits", "24"}}), "frame");
    ASSERT_EQ(frames.size(), 1u);
    EXPECT_EQ(intField(frames[0], "position"), 0x05AC53);
    EXPECT_EQ(intField(frames[0], "crc_rx"), 0b101111);
    EXPECT_TRUE(std::get<bool>(*frames[0].get("crc_ok")));
    EXPECT_EQ(intField(frames[0], "nE"), 0);
    EXPECT_EQ(intField(frames[0], "nW"), 0);
    EXPECT_TRUE(frames[0].hasError("error_bit"));
    EXPECT_TRUE(frames[0].hasError("warning_bit"));
    EXPECT_FALSE(frames[0].hasError("crc"));
}

TEST(BisscGenerator, ProducesTheV10Slots) {
    // The generator's SL, read at each MA falling edge with no line delay, is V10.
    BisscGenConfig cfg;
    cfg.bits = 13;
    BisscGenerator gen(cfg);
    BisscFrameSpec f;
    f.data = 0x0A5A;
    f.nw = 0;
    gen.addFrame(f);
    const Waveform w = gen.build();
    bool ma = true, sl = true;
    std::string seen;
    for (const Edge& e : w.edges) {
        if (e.t >= gen.frames()[0].end) break;
        if (e.line == 1) sl = e.level;
        if (e.line == 0) {
            if (ma && !e.level) seen += sl ? '1' : '0';
            ma = e.level;
        }
    }
    // The first falling edge starts the frame (SL idle 1); the next 25 read slots 0..24;
    // the stop slot 25 has no falling edge after it (CDM = 0 leaves MA high): SL is low.
    EXPECT_EQ(seen.substr(1, 25) + (sl ? "1" : "0"), "10100101001011010101010110");
}

struct SweepCase {
    double clock_hz;
    int bits;
    double delay_ns;
    double sample_rate;  // 0: 1 ns ticks
};

class BisscSweep : public ::testing::TestWithParam<SweepCase> {};

TEST_P(BisscSweep, EveryFrameExact) {
    const SweepCase c = GetParam();
    BisscGenConfig cfg;
    cfg.clock_hz = c.clock_hz;
    cfg.bits = c.bits;
    cfg.line_delay_ns = c.delay_ns;
    cfg.jitter_ns = 0.03e9 / c.clock_hz;  // 3 % of a period
    if (c.sample_rate > 0) {
        cfg.timebase = Timebase::fromSampleRate(std::int64_t(c.sample_rate));
        cfg.jitter_ns = 0;
    }
    cfg.seed = std::uint32_t(c.bits * 7 + int(c.delay_ns));
    cfg.timeout_ns = 15000 + 2e9 / c.clock_hz;
    BisscGenerator gen(cfg);
    std::mt19937_64 rng(cfg.seed);
    const std::uint64_t mask = c.bits >= 64 ? ~0ull : ((1ull << c.bits) - 1);
    for (int i = 0; i < 12; ++i) {
        BisscFrameSpec f;
        f.data = rng() & mask;
        f.ne = int(rng() % 5 != 0);
        f.nw = int(rng() % 4 != 0);
        f.cds = int(rng() & 1);
        f.cdm = int(rng() & 1);
        f.proc_cycles = int(rng() % 9);
        f.extra_clocks = int(rng() % 3) * 3;
        f.corrupt_crc = i == 5;
        gen.addFrame(f);
    }
    const auto events = decodeBissc(gen.build(), {{"bits", std::to_string(c.bits)}});
    const auto frames = ofType(events, "frame");
    if (frames.size() != gen.frames().size())
        for (const auto& e : frames)
            ADD_FAILURE() << e.start << " " << e.summary << " "
                          << ::testing::PrintToString(e.errors);
    ASSERT_EQ(frames.size(), gen.frames().size());
    const double tick_ns = cfg.timebase.nsPerTick();
    for (std::size_t i = 0; i < frames.size(); ++i) {
        const Event& e = frames[i];
        const BisscFrameTruth& t = gen.frames()[i];
        SCOPED_TRACE(::testing::Message() << "frame " << i);
        EXPECT_EQ(e.start, t.start);
        EXPECT_EQ(e.end, t.end);
        EXPECT_EQ(std::get<std::uint64_t>(*e.get("position")), t.spec.data);
        EXPECT_EQ(intField(e, "nE"), t.spec.ne);
        EXPECT_EQ(intField(e, "nW"), t.spec.nw);
        EXPECT_EQ(intField(e, "crc_rx"), t.crc_sent);
        EXPECT_EQ(std::get<bool>(*e.get("crc_ok")), t.crc_ok);
        EXPECT_EQ(e.hasError("crc"), !t.crc_ok);
        EXPECT_EQ(intField(e, "cds"), t.spec.cds);
        EXPECT_EQ(intField(e, "cdm"), t.spec.cdm);
        EXPECT_EQ(intField(e, "proc_cycles"), t.spec.proc_cycles);
        EXPECT_EQ(intField(e, "extra_clocks"), t.spec.extra_clocks);
        EXPECT_NEAR(double(intField(e, "line_delay_ns")), c.delay_ns,
                    2 * tick_ns + 2 * cfg.jitter_ns + 1);
        EXPECT_NEAR(std::get<double>(*e.get("clock_hz")), c.clock_hz, c.clock_hz * 0.02);
        EXPECT_FALSE(e.hasError("short_frame"));
    }
}

INSTANTIATE_TEST_SUITE_P(Rates, BisscSweep,
                         ::testing::Values(SweepCase{80e3, 8, 0, 0}, SweepCase{80e3, 48, 1500, 0},
                                           SweepCase{250e3, 26, 300, 0}, SweepCase{1e6, 13, 0, 0},
                                           SweepCase{1e6, 32, 1500, 0}, SweepCase{2e6, 24, 750, 0},
                                           SweepCase{5e6, 40, 1000, 0}, SweepCase{10e6, 32, 0, 0},
                                           SweepCase{10e6, 48, 1500, 0}, SweepCase{10e6, 8, 550, 0},
                                           // Sampled captures: 10 MHz at 24 MHz (2.4 samples per
                                           // bit), as the real Renishaw capture; 2 MHz at 24 MHz.
                                           SweepCase{10e6, 32, 60, 24e6},
                                           SweepCase{10e6, 26, 1200, 24e6},
                                           SweepCase{2e6, 32, 80, 24e6},
                                           SweepCase{5e6, 48, 400, 50e6}));

TEST(BisscFrames, StSplitAndMt) {
    BisscGenConfig cfg;
    cfg.bits = 32;
    BisscGenerator gen(cfg);
    BisscFrameSpec f;
    f.data = 0xABC12345;  // MT 12 bits 0xABC, ST 20 bits 0x12345
    gen.addFrame(f);
    auto frames = ofType(decodeBissc(gen.build(), {{"bits", "32"}, {"mt_bits", "12"}}), "frame");
    ASSERT_EQ(frames.size(), 1u);
    EXPECT_EQ(intField(frames[0], "position"), 0xABC12345);
    EXPECT_EQ(intField(frames[0], "st"), 0x12345);
    EXPECT_EQ(intField(frames[0], "mt"), 0xABC);
}

TEST(BisscFrames, Crc16Encoder) {
    BisscGenConfig cfg;
    cfg.bits = 32;
    cfg.crc_poly = 0x190D9;
    BisscGenerator gen(cfg);
    BisscFrameSpec f;
    f.data = 0x12345678;
    gen.addFrame(f);
    f.corrupt_crc = true;
    gen.addFrame(f);
    auto frames =
        ofType(decodeBissc(gen.build(), {{"bits", "32"}, {"crc_poly", "0x190D9"}}), "frame");
    ASSERT_EQ(frames.size(), 2u);
    EXPECT_EQ(intField(frames[0], "position"), 0x12345678);
    EXPECT_TRUE(std::get<bool>(*frames[0].get("crc_ok")));
    EXPECT_EQ(intField(frames[0], "crc_rx"), gen.frames()[0].crc_sent);
    EXPECT_TRUE(frames[1].hasError("crc"));
}

TEST(BisscFrames, HoldCdmFramesStartFromMaLow) {
    BisscGenConfig cfg;
    cfg.bits = 26;
    cfg.hold_cdm = true;
    cfg.line_delay_ns = 400;
    BisscGenerator gen(cfg);
    const int cdm[] = {1, 1, 0, 1, 0, 0, 1, 1};
    for (int i = 0; i < 8; ++i) {
        BisscFrameSpec f;
        f.data = std::uint64_t(i) * 1234567;
        f.cdm = cdm[i];
        gen.addFrame(f);
    }
    auto frames = ofType(decodeBissc(gen.build(), {}), "frame");
    ASSERT_EQ(frames.size(), 8u);
    for (int i = 0; i < 8; ++i) {
        SCOPED_TRACE(i);
        EXPECT_EQ(intField(frames[i], "position"), std::int64_t(i) * 1234567);
        EXPECT_EQ(intField(frames[i], "cdm"), cdm[i]);
        EXPECT_EQ(std::get<bool>(*frames[i].get("hold_cdm")), i > 0 && cdm[i - 1] == 1);
        EXPECT_EQ(frames[i].start, gen.frames()[i].start);
        EXPECT_TRUE(frames[i].errors.empty());
    }
}

TEST(BisscFrames, CdmOneWithoutHoldReturnsToIdle) {
    BisscGenConfig cfg;
    BisscGenerator gen(cfg);
    for (int i = 0; i < 4; ++i) {
        BisscFrameSpec f;
        f.data = 100 + i;
        f.cdm = 1;
        gen.addFrame(f);
    }
    auto frames = ofType(decodeBissc(gen.build(), {}), "frame");
    ASSERT_EQ(frames.size(), 4u);
    for (int i = 0; i < 4; ++i) {
        EXPECT_EQ(intField(frames[i], "position"), 100 + i);
        EXPECT_EQ(intField(frames[i], "cdm"), 1);
        EXPECT_FALSE(std::get<bool>(*frames[i].get("hold_cdm")));
        EXPECT_EQ(frames[i].start, gen.frames()[i].start);
    }
}

TEST(BisscFrames, ReturnToIdleFrameMeasuresItsOwnDelay) {
    // After a CDM = 1 frame the master returns MA to idle with a rise, and the next
    // frame's first rise is only found at its ACK, when that idle rise is dropped from
    // the frame's rises (and from its mean period). The ACK delay is then compared with
    // the previous frame's delay within a quarter of that period: here the cable's delay
    // changes by half a bit between the frames, so the previous delay must not be
    // mixed in, and the second frame reports its own.
    BisscGenConfig cfg;
    cfg.line_delay_ns = 200;
    BisscGenerator gen(cfg);
    for (int i = 0; i < 2; ++i) {
        BisscFrameSpec f;
        f.data = 200 + i;
        f.cdm = 1;
        gen.addFrame(f);
    }
    Waveform w = gen.build();
    const Tick shift = 500;  // ns = ticks: half of the 1 MHz clock's period
    const auto& second = gen.frames()[1];
    for (auto& e : w.edges)
        if (e.line == 1 && e.t > second.start && e.t <= second.end) e.t += shift;
    std::stable_sort(w.edges.begin(), w.edges.end(),
                     [](const Edge& a, const Edge& b) { return a.t < b.t; });
    w.end += shift;

    auto frames = ofType(decodeBissc(w, {}), "frame");
    ASSERT_EQ(frames.size(), 2u);
    EXPECT_EQ(intField(frames[0], "line_delay_ns"), 200);
    EXPECT_EQ(intField(frames[1], "line_delay_ns"), 700);
    EXPECT_EQ(intField(frames[1], "position"), 201);
    EXPECT_TRUE(frames[1].errors.empty());
}

TEST(BisscFrames, TruncatedFrameIsShortAndTheNextDecodes) {
    // With the slave's usual 20 us timeout and a short 5 us one. The master pauses about
    // 15 us between a cut frame and the next: less than the 20 us that end a frame when
    // nothing else tells, but three times a 5 us slave's timeout (learnt from the frames
    // before, or seen as SL rising long after the last slot), so the next clocks are a
    // new request, not the cut frame going on.
    for (double timeout : {20000.0, 5000.0}) {
        SCOPED_TRACE(timeout);
        BisscGenConfig cfg;
        cfg.line_delay_ns = 200;
        cfg.timeout_ns = timeout;
        BisscGenerator gen(cfg);
        BisscFrameSpec f;
        f.data = 0x2AAAAAA;
        for (int cut : {12, 3, 1, 30}) {  // mid data, start bit only, LAT only, in the CRC
            f.truncate_after = cut;
            gen.addFrame(f);
            f.truncate_after = -1;
            gen.addFrame(f);
        }
        auto frames = ofType(decodeBissc(gen.build(), {}), "frame");
        ASSERT_EQ(frames.size(), 8u);
        for (int i = 0; i < 8; i += 2) {
            SCOPED_TRACE(i);
            EXPECT_FALSE(frames[i].errors.empty());
            EXPECT_TRUE(nullField(frames[i], "position"));
            EXPECT_EQ(intField(frames[i + 1], "position"), 0x2AAAAAA);
            EXPECT_TRUE(frames[i + 1].errors.empty());
        }
        EXPECT_TRUE(frames[0].hasError("short_frame"));
        EXPECT_TRUE(frames[2].hasError("short_frame"));  // start bit sent, then nothing
        EXPECT_TRUE(frames[4].hasError("no_ack"));
        EXPECT_TRUE(frames[6].hasError("short_frame"));
    }
}

// Frames closer together than the 20 us that end a quiet frame when nothing else tells
// (10 MHz, a 2 us timeout, 3 us between frames), from a slave that answers none of the
// first five: each is a frame of its own with no ACK, not one frame across all five,
// and the frames it answers after them decode clean.
TEST(BisscFrames, UnansweredFramesCloseTogetherStaySeparate) {
    BisscGenConfig cfg;
    cfg.clock_hz = 10e6;
    cfg.timeout_ns = 2000;
    cfg.idle_ns = 3000;
    BisscGenerator gen(cfg);
    BisscFrameSpec f;
    for (int i = 0; i < 12; ++i) {
        f.data = 0x100000u + std::uint64_t(i);
        gen.addFrame(f);
    }
    Waveform w = gen.build();
    const int silent = 5;
    const Tick answered_from = gen.frames()[silent].start;
    std::erase_if(w.edges, [&](const Edge& e) { return e.line == 1 && e.t < answered_from; });

    auto frames = ofType(decodeBissc(w, {}), "frame");
    ASSERT_EQ(frames.size(), 12u);
    for (int i = 0; i < 12; ++i) {
        SCOPED_TRACE(i);
        EXPECT_EQ(frames[i].start, gen.frames()[i].start);
        if (i < silent) {
            EXPECT_TRUE(frames[i].hasError("no_ack"));
            EXPECT_TRUE(nullField(frames[i], "position"));
        } else {
            EXPECT_TRUE(frames[i].errors.empty());
            EXPECT_EQ(intField(frames[i], "position"), 0x100000 + i);
        }
    }
}

// A capture that starts anywhere inside a frame, without $dumpvars: a line's level is
// its value on the first time line, or 1 until its first change. Whatever the frame in
// progress comes out as, the whole frames after it decode clean. Frames 6.89 us apart (10 MHz,
// 100 MS/s, a 2.04 us timeout), closer than the 20 us that end a quiet frame when nothing else
// tells. Before, a start where SL was really low made MA's pause before the next frame count as a
// clock phase of the frame; every pause between frames then looked like clocking, and the rest of
// the capture ran into one frame.
TEST(BisscFrames, ACaptureStartingInsideAFrameDecodesTheFramesAfterIt) {
    BisscGenerator gen(tenMhzAt100Msps());
    BisscFrameSpec f;
    for (int i = 0; i < 12; ++i) {
        f.data = 0x200000u + std::uint64_t(i) * 0x1357u;
        gen.addFrame(f);
    }
    const Waveform whole = gen.build();
    const Tick from = gen.frames()[1].start, to = gen.frames()[2].start;
    const Tick first_judged = gen.frames()[3].start;
    for (Tick cut = from; cut < to; ++cut) {
        SCOPED_TRACE(cut);
        auto frames = ofType(decodeBissc(startingAt(whole, cut), {}), "frame");
        // What the frame cut became, then frames 2..11, each whole after the cut. The
        // first of them may go with the frame cut: a pause after a lone MA pulse cannot
        // be told from a slow clock before a first frame has shown the clock's rate.
        std::erase_if(frames, [&](const Event& e) { return e.start < first_judged; });
        ASSERT_EQ(frames.size(), 9u);
        for (std::size_t i = 0; i < frames.size(); ++i) {
            EXPECT_EQ(frames[i].start, gen.frames()[i + 3].start) << i;
            EXPECT_TRUE(frames[i].errors.empty()) << i;
            EXPECT_EQ(intField(frames[i], "position"), 0x200000 + int(i + 3) * 0x1357) << i;
        }
    }
}

TEST(BisscFrames, CaptureEndingMidFrameIsShort) {
    BisscGenConfig cfg;
    BisscGenerator gen(cfg);
    BisscFrameSpec f;
    f.data = 77;
    gen.addFrame(f);
    Waveform w = gen.build();
    // Cut the capture in the middle of the frame's data.
    const Tick cut = gen.frames()[0].start + w.timebase.fromNs(15000);
    std::erase_if(w.edges, [&](const Edge& e) { return e.t > cut; });
    w.end = cut;
    auto frames = ofType(decodeBissc(w, {}), "frame");
    ASSERT_EQ(frames.size(), 1u);
    EXPECT_TRUE(frames[0].hasError("short_frame"));
}

TEST(BisscFrames, GlitchesAreFilteredAndFlagged) {
    BisscGenConfig cfg;
    cfg.clock_hz = 1e6;
    BisscGenerator gen(cfg);
    BisscFrameSpec f;
    f.data = 0x1555555;
    gen.addFrame(f);
    gen.addFrame(f);
    gen.addFrame(f);
    // A 20 ns pulse on MA in the middle of a high phase of frame 1, and one on SL in frame 2.
    const double f1 = double(gen.frames()[1].start) + 500 + 10 * 1000 + 200;
    gen.addGlitch(0, f1, 20);
    const double f2 = double(gen.frames()[2].start) + 500 + 15 * 1000 + 300;
    gen.addGlitch(1, f2, 20);
    const Waveform w = gen.build();

    auto raw = ofType(decodeBissc(w, {}), "frame");
    ASSERT_EQ(raw.size(), 3u);
    EXPECT_TRUE(raw[1].hasError("crc") || raw[1].hasError("short_frame") ||
                intField(raw[1], "extra_clocks") != 0);

    auto frames = ofType(decodeBissc(w, {{"glitch_ns", "50"}}), "frame");
    ASSERT_EQ(frames.size(), 3u);
    for (int i = 0; i < 3; ++i) {
        EXPECT_EQ(intField(frames[i], "position"), 0x1555555);
        EXPECT_TRUE(std::get<bool>(*frames[i].get("crc_ok")));
        EXPECT_EQ(frames[i].hasError("glitch"), i > 0) << i;
    }
}

TEST(BisscFrames, PulseOnSlDuringTheTimeoutDoesNotShortenLaterFrames) {
    // A 100 ns pulse on SL just after the first frame's stop bit was sampled ends that
    // frame's timeout early as far as the decoder can tell (700 ns after the last rise).
    // The slave's timeout it learns from it, for the clock pauses of later frames, must
    // not drop below the clock's own phases (500 ns +- 150 ns of jitter at each edge).
    BisscGenConfig cfg;
    cfg.line_delay_ns = 100;
    cfg.jitter_ns = 150;
    BisscGenerator gen(cfg);
    for (int i = 0; i < 3; ++i) {
        BisscFrameSpec f;
        f.data = 300 + unsigned(i);
        gen.addFrame(f);
    }
    const double stop_ns = double(gen.frames()[0].end) - cfg.timeout_ns;  // ticks are ns
    gen.addGlitch(1, stop_ns + 600, 100);  // the stop bit is sampled 500 ns in
    auto frames = ofType(decodeBissc(gen.build(), {}), "frame");
    ASSERT_EQ(frames.size(), 3u);
    for (int i = 1; i < 3; ++i) {
        SCOPED_TRACE(i);
        EXPECT_EQ(intField(frames[std::size_t(i)], "position"), 300 + i);
        EXPECT_TRUE(frames[std::size_t(i)].errors.empty());
    }
}

TEST(BisscFrames, TimeoutShortOption) {
    BisscGenConfig cfg;
    cfg.timeout_ns = 10000;
    BisscGenerator gen(cfg);
    BisscFrameSpec f;
    gen.addFrame(f);
    auto plain = ofType(decodeBissc(gen.build(), {}), "frame");
    ASSERT_EQ(plain.size(), 1u);
    EXPECT_EQ(intField(plain[0], "timeout_ns"), 10000);
    EXPECT_FALSE(plain[0].hasError("timeout_short"));
    auto strict = ofType(decodeBissc(gen.build(), {{"timeout_min_us", "12.5"}}), "frame");
    ASSERT_EQ(strict.size(), 1u);
    EXPECT_TRUE(strict[0].hasError("timeout_short"));
}

TEST(BisscFrames, BadOptionsAreInputErrors) {
    BisscGenerator gen(BisscGenConfig{});
    gen.addFrame({});
    const Waveform w = gen.build();
    EXPECT_THROW(decodeBissc(w, {{"bits", "20"}, {"st_bits", "16"}, {"mt_bits", "8"}}), InputError);
    EXPECT_THROW(decodeBissc(w, {{"crc_poly", "0x43"}, {"crc_bits", "16"}}), InputError);
    EXPECT_THROW(decodeBissc(w, {{"bits", "65"}}), InputError);
}

TEST(BisscFrames, SlaveReadyWhileMasterClocksPastTheStopBit) {
    // The MB5U + RESOLUTE pattern: the slave raises SL 1.5 us after the stop bit while
    // the master still clocks, and answers the remaining clocks as a new request. The
    // frame keeps all its clocks; its CDM is the MA level when SL finally rises.
    for (double delay : {0.0, 300.0}) {
        BisscGenConfig cfg;
        cfg.bits = 32;
        cfg.clock_hz = 1e6;
        cfg.line_delay_ns = delay;
        cfg.ready_after_stop_ns = 1500;
        BisscGenerator gen(cfg);
        for (int extra : {5, 2, 8, 1}) {
            BisscFrameSpec f;
            f.data = 0xB19DB5F1u + unsigned(extra);
            f.proc_cycles = 15;
            f.extra_clocks = extra;
            f.cdm = extra == 8;
            gen.addFrame(f);
        }
        auto frames = ofType(decodeBissc(gen.build(), {{"bits", "32"}}), "frame");
        ASSERT_EQ(frames.size(), 4u);
        for (int i = 0; i < 4; ++i) {
            SCOPED_TRACE(i);
            const auto& t = gen.frames()[i];
            EXPECT_EQ(std::get<std::uint64_t>(*frames[i].get("position")), t.spec.data);
            EXPECT_EQ(intField(frames[i], "clocks"), t.rises);
            EXPECT_EQ(intField(frames[i], "extra_clocks"), t.spec.extra_clocks);
            EXPECT_EQ(std::get<bool>(*frames[i].get("retriggered")), t.retriggered);
            EXPECT_EQ(intField(frames[i], "cdm"), t.spec.cdm);
            EXPECT_EQ(frames[i].end, t.end);
            EXPECT_TRUE(frames[i].errors.empty());
        }
        EXPECT_TRUE(gen.frames()[0].retriggered);
        EXPECT_TRUE(gen.frames()[1].retriggered);   // one clock after ready: LAT, no ACK
        EXPECT_FALSE(gen.frames()[3].retriggered);  // clocking ends before the slave is ready
    }
}

TEST(BisscFrames, ClocksPastTheStopBitAreJudgedByTheDataClock) {
    // Whether MA still clocks after the slave's timeout ended early is judged against the
    // longest clock phases of the frame, the data's included (the decoder's fast path
    // for data edges records them too). Here the master's first three phases (start,
    // LAT, the fall before the 2nd rise) are squeezed to 0.4 of the 500 ns data phases;
    // the clocks past the stop bit run at the data's pace, and must still count as
    // clocks: the frame keeps them and is retriggered.
    BisscGenConfig cfg;
    cfg.bits = 32;
    cfg.clock_hz = 1e6;
    cfg.ready_after_stop_ns = 1500;
    BisscGenerator gen(cfg);
    BisscFrameSpec f;
    f.data = 0xB19DB5F6u;
    f.proc_cycles = 15;
    f.extra_clocks = 5;
    gen.addFrame(f);
    Waveform w = gen.build();
    std::vector<Edge*> ma;
    for (auto& e : w.edges)
        if (e.line == 0 && ma.size() < 4) ma.push_back(&e);
    ASSERT_EQ(ma.size(), 4u);
    ASSERT_FALSE(ma[0]->level);  // start, LAT, fall, 2nd rise
    const Tick phase = ma[3]->t - ma[2]->t;
    for (int i = 0; i < 3; ++i)
        ma[i]->t = ma[3]->t - (3 - i) * phase * 2 / 5;
    for (std::size_t i = 1; i < w.edges.size(); ++i)
        ASSERT_LE(w.edges[i - 1].t, w.edges[i].t);

    auto frames = ofType(decodeBissc(w, {{"bits", "32"}}), "frame");
    ASSERT_EQ(frames.size(), 1u);
    const auto& t = gen.frames()[0];
    ASSERT_TRUE(t.retriggered);
    EXPECT_EQ(std::get<std::uint64_t>(*frames[0].get("position")), f.data);
    EXPECT_EQ(intField(frames[0], "clocks"), t.rises);
    EXPECT_EQ(intField(frames[0], "extra_clocks"), f.extra_clocks);
    EXPECT_TRUE(std::get<bool>(*frames[0].get("retriggered")));
    EXPECT_TRUE(frames[0].errors.empty());
}

TEST(BisscFrames, RandomConfigurationsDecodeExactly) {
    // 40 seeded random set-ups across the BiSS range: 80 kHz..10 MHz, 8..48 bits,
    // 0..1.5 us line delay, 0..8 busy clocks, jitter, 1 ns ticks or >= 10 samples per bit.
    std::mt19937_64 rng(20261122);
    auto uni = [&](double a, double b) {
        return std::uniform_real_distribution<double>(a, b)(rng);
    };
    for (int run = 0; run < 40; ++run) {
        BisscGenConfig cfg;
        cfg.clock_hz = std::exp(uni(std::log(80e3), std::log(10e6)));
        cfg.bits = 8 + int(rng() % 41);
        cfg.line_delay_ns = uni(0, 1500);
        cfg.jitter_ns = uni(0, 0.04) * 1e9 / cfg.clock_hz;
        cfg.timeout_ns = uni(12500, 40000) + 1e9 / cfg.clock_hz;
        cfg.idle_ns = uni(1000, 20000);
        cfg.hold_cdm = rng() & 1;
        cfg.seed = std::uint32_t(rng());
        if (rng() % 3 == 0) {
            cfg.timebase = Timebase::fromSampleRate(std::int64_t(cfg.clock_hz * uni(10, 40)));
            cfg.jitter_ns = 0;
        }
        SCOPED_TRACE(::testing::Message() << "run " << run << ": " << cfg.clock_hz << " Hz, "
                                          << cfg.bits << " bits, delay " << cfg.line_delay_ns);
        BisscGenerator gen(cfg);
        for (int i = 0; i < 6; ++i) {
            BisscFrameSpec f;
            f.data = rng() & ((1ull << cfg.bits) - 1);
            f.ne = int(rng() % 4 != 0);
            f.nw = int(rng() % 4 != 0);
            f.cds = int(rng() & 1);
            f.cdm = int(rng() & 1);
            f.proc_cycles = int(rng() % 9);
            f.extra_clocks = int(rng() % 4);
            f.corrupt_crc = rng() % 5 == 0;
            gen.addFrame(f);
        }
        const auto frames =
            ofType(decodeBissc(gen.build(), {{"bits", std::to_string(cfg.bits)}}), "frame");
        ASSERT_EQ(frames.size(), gen.frames().size());
        for (std::size_t i = 0; i < frames.size(); ++i) {
            const auto& t = gen.frames()[i];
            EXPECT_EQ(frames[i].start, t.start) << i;
            EXPECT_EQ(std::get<std::uint64_t>(*frames[i].get("position")), t.spec.data) << i;
            EXPECT_EQ(std::get<bool>(*frames[i].get("crc_ok")), t.crc_ok) << i;
            EXPECT_EQ(intField(frames[i], "cds"), t.spec.cds) << i;
            EXPECT_EQ(intField(frames[i], "cdm"), t.spec.cdm) << i;
            EXPECT_EQ(intField(frames[i], "proc_cycles"), t.spec.proc_cycles) << i;
            EXPECT_EQ(intField(frames[i], "extra_clocks"), t.spec.extra_clocks) << i;
            EXPECT_NEAR(double(intField(frames[i], "line_delay_ns")), cfg.line_delay_ns,
                        cfg.timebase.nsPerTick() + cfg.jitter_ns + 1)
                << i;
        }
    }
}

TEST(BisscFrames, WidestFramesCheckTheirCrc) {
    // The CRC covers the data, nE and nW: 66 bits for 64 data bits, past one 64-bit word
    // (FixedLengthCrc's high part). Every width from 60 up, right and corrupted CRCs.
    std::mt19937_64 rng(33);
    for (int bits = 60; bits <= 64; ++bits) {
        SCOPED_TRACE(::testing::Message() << bits << " bits");
        BisscGenConfig cfg;
        cfg.bits = bits;
        cfg.seed = std::uint32_t(bits);
        BisscGenerator gen(cfg);
        for (int i = 0; i < 8; ++i) {
            BisscFrameSpec f;
            f.data = lowBits(rng(), bits);
            f.ne = int(rng() & 1);
            f.nw = int(rng() & 1);
            f.corrupt_crc = i % 2 == 1;
            gen.addFrame(f);
        }
        const auto frames =
            ofType(decodeBissc(gen.build(), {{"bits", std::to_string(bits)}}), "frame");
        ASSERT_EQ(frames.size(), gen.frames().size());
        for (std::size_t i = 0; i < frames.size(); ++i) {
            const auto& t = gen.frames()[i];
            EXPECT_EQ(std::get<std::uint64_t>(*frames[i].get("position")), t.spec.data) << i;
            EXPECT_EQ(std::get<bool>(*frames[i].get("crc_ok")), t.crc_ok) << i;
            EXPECT_EQ(t.crc_ok, i % 2 == 0) << i;
        }
    }
}

TEST(BisscFrames, NoiseNeverBreaksTheDecoder) {
    // Random toggles on both lines (and a valid frame in between): faults are reported
    // as events, events stay in time order, and the frame after the noise decodes.
    std::mt19937_64 rng(4);
    for (int run = 0; run < 20; ++run) {
        WaveBuilder b(Timebase{1, 1'000'000'000}, {"MA", "SLO"}, {1, 1});
        double t = 100;
        for (int i = 0; i < 400; ++i) {
            t += double(rng() % 3000) + 1;
            b.setNs(std::uint32_t(rng() & 1), t, rng() & 1);
        }
        b.setNs(0, t + 1, true);
        b.setNs(1, t + 1, true);
        Waveform noise = b.build(b.ticksFromNs(t + 100000));
        BisscGenConfig cfg;
        cfg.lead_ns = t + 100000;
        BisscGenerator gen(cfg);
        BisscFrameSpec f;
        f.data = 0x155AA55;
        gen.addFrame(f);
        Waveform w = gen.build();
        w.edges.insert(w.edges.begin(), noise.edges.begin(), noise.edges.end());
        const auto events = decodeBissc(w, {});
        ASSERT_FALSE(events.empty());
        for (std::size_t i = 0; i < events.size(); ++i) {
            EXPECT_LE(events[i].start, events[i].end);
            if (i > 0) {
                EXPECT_LE(events[i - 1].start, events[i].start);
            }
        }
        const Event last = ofType(events, "frame").back();
        EXPECT_EQ(intField(last, "position"), 0x155AA55) << run;
        EXPECT_TRUE(last.errors.empty()) << run;
    }
}

TEST(BisscFrames, LongCaptureIsFastAndFlat) {
    // 3000 frames at 10 MHz, 32 bits: decoding is linear in edges (well under a second).
    BisscGenConfig cfg;
    cfg.clock_hz = 10e6;
    cfg.bits = 32;
    cfg.line_delay_ns = 500;
    cfg.timeout_ns = 12500;
    cfg.idle_ns = 1000;
    BisscGenerator gen(cfg);
    std::mt19937_64 rng(5);
    for (int i = 0; i < 3000; ++i) {
        BisscFrameSpec f;
        f.data = rng() & 0xFFFFFFFFull;
        f.proc_cycles = 2;
        gen.addFrame(f);
    }
    const auto frames = ofType(decodeBissc(gen.build(), {{"bits", "32"}}), "frame");
    ASSERT_EQ(frames.size(), 3000u);
    int bad = 0;
    for (std::size_t i = 0; i < frames.size(); ++i)
        bad += std::get<std::uint64_t>(*frames[i].get("position")) != gen.frames()[i].spec.data;
    EXPECT_EQ(bad, 0);
}

TEST(BisscFrameVectors, V1toV9_CrcsAsDecodedFrames) {
    // docs/protocols.md §4.1: each CRC vector sent as a frame (the vector's input = data, nE,
    // nW) with the published CRC must decode with that crc_rx and a good CRC.
    struct Vec {
        int bits;
        std::uint64_t data;
        int ne, nw;
        std::uint32_t crc;
        const char* poly;
    };
    const Vec vectors[] = {
        {10, 0b0100110101, 0, 1, 0x1C, "0x43"},               // V1 AN21 (12 bits incl. E, W)
        {24, 0x05AC53, 0, 0, 0b101111, "0x43"},               // V2 AN18
        {26, 0x0000000, 1, 1, 0x3A, "0x43"},                  // V3
        {26, 0x3FFFFFF, 1, 1, 0x22, "0x43"},                  // V4
        {24, 0x123456, 1, 1, 0x35, "0x43"},                   // V5
        {13, 0x0A5A, 1, 0, 0x2B, "0x43"},                     // V6
        {18, 0x2AAAA, 0, 1, 0x2D, "0x43"},                    // V7
        {32, 0x12345678, 0, 0, 0x00, "0x43"},                 // V8
        {38, 0xD9CFE0C0DAull >> 2, 1, 0, 0x5F29, "0x190D9"},  // V9 AN21 CRC16
    };
    for (const Vec& v : vectors) {
        SCOPED_TRACE(v.bits);
        const int crc_bits = std::string(v.poly) == "0x43" ? 6 : 16;
        std::string slots =
            "1"
            "0"
            "1"
            "0";  // LAT ACK start CDS
        for (int i = v.bits - 1; i >= 0; --i)
            slots += char('0' + ((v.data >> i) & 1));
        slots += char('0' + v.ne);
        slots += char('0' + v.nw);
        for (int i = crc_bits - 1; i >= 0; --i)
            slots += char('0' + ((v.crc >> i) & 1));
        slots += '0';
        auto frames = ofType(decodeBissc(fromSlots(slots, 1000, 100),
                                         {{"bits", std::to_string(v.bits)}, {"crc_poly", v.poly}}),
                             "frame");
        ASSERT_EQ(frames.size(), 1u);
        EXPECT_EQ(std::get<std::uint64_t>(*frames[0].get("position")), v.data);
        EXPECT_EQ(intField(frames[0], "crc_rx"), v.crc);
        EXPECT_TRUE(std::get<bool>(*frames[0].get("crc_ok")));
        EXPECT_FALSE(frames[0].hasError("crc"));
    }
}
