// The SPI decoder against its own generator: known words in every mode, width and bit
// order, several words per cs, words cut short by cs, framing without cs.
#include <gtest/gtest.h>

#include <random>

#include "capture/capture_reader.h"
#include "core/registry.h"
#include "core/session.h"
#include "sinks/event_format.h"
#include "spi_generator.h"
#include "spi_info.h"
#include "support/decode_events.h"

using namespace busdecode;

namespace {

struct Register {
    Register() { Registry::instance().add(makeSpiFactory()); }
} const register_spi;

std::uint64_t mask(int bits) {
    return bits >= 64 ? ~0ull : ((1ull << bits) - 1);
}

std::vector<Event> decode(const Waveform& w, std::map<std::string, std::string> opts,
                          std::map<std::string, std::string> map = {}) {
    return decodeWaveform(w, {DecoderRequest{"spi", std::move(map), std::move(opts)}});
}

std::uint64_t u(const Event& e, const char* key) {
    return std::get<std::uint64_t>(*e.get(key));
}

// Tick of the sampling clock edge of bit k in a transfer starting (cs) at t0 ns.
Tick sampleTick(const SpiTiming& tm, const SpiMode& m, double t0, int k) {
    double lead = t0 + tm.cs_setup_ns + k * tm.period_ns;
    return Tick(std::llround(m.cpha == 0 ? lead : lead + tm.period_ns / 2));
}

}  // namespace

class SpiModes : public ::testing::TestWithParam<std::tuple<int, int, bool, int>> {};

TEST_P(SpiModes, RandomWordsDecodeExactly) {
    auto [cpol, cpha, lsb, bits] = GetParam();
    SpiMode mode{cpol, cpha, lsb, false};
    SpiTiming tm;
    std::mt19937_64 rng(1234 + cpol * 2 + cpha + bits * 7 + lsb);
    std::vector<std::vector<SpiGenerator::Word>> transfers;
    for (int i = 0; i < 20; ++i)
        transfers.push_back({{rng() & mask(bits), rng() & mask(bits)}});
    const double gap = 1000;
    Waveform w = makeSpiCapture(transfers, bits, mode, tm, gap);
    auto ev = decode(w, {{"cpol", std::to_string(cpol)},
                         {"cpha", std::to_string(cpha)},
                         {"lsb_first", lsb ? "1" : "0"},
                         {"bits", std::to_string(bits)}});
    ASSERT_EQ(ev.size(), transfers.size());
    double t0 = gap;
    for (std::size_t i = 0; i < ev.size(); ++i) {
        SCOPED_TRACE(i);
        EXPECT_EQ(ev[i].proto, "spi");
        EXPECT_EQ(ev[i].type, "transfer");
        EXPECT_TRUE(ev[i].errors.empty());
        EXPECT_EQ(u(ev[i], "mosi"), transfers[i][0].mosi);
        EXPECT_EQ(u(ev[i], "miso"), transfers[i][0].miso);
        EXPECT_EQ(asInt(*ev[i].get("bits")), bits);
        EXPECT_EQ(ev[i].start, sampleTick(tm, mode, t0, 0));
        // One bit period after the last sampling edge (sigrok's convention); a 1-bit word
        // has no period to go by and ends where it starts.
        Tick last = sampleTick(tm, mode, t0, bits - 1);
        EXPECT_EQ(ev[i].end, bits > 1 ? last + Tick(tm.period_ns) : last);
        t0 += tm.cs_setup_ns + bits * tm.period_ns - tm.period_ns / 2 + tm.cs_hold_ns + gap;
    }
}

INSTANTIATE_TEST_SUITE_P(AllModes, SpiModes,
                         ::testing::Combine(::testing::Values(0, 1), ::testing::Values(0, 1),
                                            ::testing::Bool(),
                                            ::testing::Values(1, 8, 13, 32, 64)));

TEST(Spi, DefaultsAreMode3Msb32) {
    Waveform w = makeSpiCapture({{{0x80000000, 0x10001B2E}}}, 32);
    auto ev = decode(w, {});
    ASSERT_EQ(ev.size(), 1u);
    EXPECT_EQ(u(ev[0], "mosi"), 0x80000000u);
    EXPECT_EQ(u(ev[0], "miso"), 0x10001B2Eu);
    EXPECT_EQ(ev[0].summary, "MOSI 0x80000000 MISO 0x10001B2E");
}

TEST(Spi, WrongModeGivesOtherWords) {
    // Decoding mode-3 traffic as mode 0 must not silently give the same words: the
    // test would pass for a decoder that ignores cpol/cpha otherwise.
    Waveform w = makeSpiCapture({{{0xA5A5A5A5, 0x0F0F0F0F}}}, 32);
    auto ev = decode(w, {{"cpha", "0"}});
    ASSERT_FALSE(ev.empty());
    EXPECT_NE(u(ev[0], "mosi"), 0xA5A5A5A5u);
}

TEST(Spi, SeveralWordsInOneCsAssertion) {
    std::vector<SpiGenerator::Word> words = {
        {0x80, 0x01}, {0x00, 0x02}, {0xFF, 0x03}, {0x5A, 0x04}};
    Waveform w = makeSpiCapture({words}, 8);
    auto ev = decode(w, {{"bits", "8"}});
    ASSERT_EQ(ev.size(), 4u);
    for (std::size_t i = 0; i < 4; ++i) {
        EXPECT_EQ(u(ev[i], "mosi"), words[i].mosi);
        EXPECT_EQ(u(ev[i], "miso"), words[i].miso);
        EXPECT_TRUE(ev[i].errors.empty());
    }
}

namespace {

// A 32-bit word cut short by cs after 20 bits, then a whole one.
Waveform cutShortThenWhole() {
    WaveBuilder wb(Timebase{1, 1'000'000'000}, {"cs", "sclk", "mosi", "miso"},
                   SpiGenerator::idleLevels({}));
    SpiGenerator gen(wb, {0, 1, 2, 3});
    double t = gen.transfer(1000, {{0xDEADBEEF, 0x12345678}}, 32, 20);
    t = gen.transfer(t + 1000, 0xCAFEF00D, 0x87654321, 32);
    return wb.build(wb.ticksFromNs(t + 1000));
}

}  // namespace

TEST(Spi, WordCutShortByCsIsReportedWithItsBits) {
    auto ev = decode(cutShortThenWhole(), {});
    ASSERT_EQ(ev.size(), 2u);
    EXPECT_EQ(ev[0].errors, std::vector<std::string>{"short_frame"});
    EXPECT_EQ(asInt(*ev[0].get("bits")), 20);
    EXPECT_EQ(u(ev[0], "mosi"), 0xDEADBEEFu >> 12);  // the first 20 bits sent, MSB first
    EXPECT_EQ(u(ev[0], "miso"), 0x12345678u >> 12);
    EXPECT_TRUE(ev[1].errors.empty());
    EXPECT_EQ(u(ev[1], "mosi"), 0xCAFEF00Du);
    EXPECT_EQ(u(ev[1], "miso"), 0x87654321u);
}

TEST(Spi, TextOutputGetsTheSummaryWithoutFields) {
    // A sink that reads no fields (text output) gets the same events, summaries and errors
    // as one that does, without the fields; with MISO unbound, one line's text and
    // fields are left out either way.
    const Waveform bound = cutShortThenWhole();
    struct SummaryOnly : OutputSink {
        std::vector<Event> events;
        void onEvent(const Event& e, const CaptureFacts&) override { events.push_back(e); }
        bool readsFields() const override { return false; }
    };
    for (bool miso : {true, false}) {
        SCOPED_TRACE(miso ? "miso bound" : "miso unbound");
        Waveform w = bound;
        if (!miso) w.names = {"cs", "sclk", "mosi", "unrelated"};
        const auto with_fields = decode(w, {});
        SummaryOnly text;
        auto reader = memoryReader(w);
        Session s({DecoderRequest{"spi", {}, {}}}, *reader, "memory");
        s.addSink(&text);
        s.run();
        ASSERT_EQ(text.events.size(), 2u);
        ASSERT_EQ(with_fields.size(), 2u);
        for (std::size_t i = 0; i < 2; ++i) {
            EXPECT_TRUE(text.events[i].fields.empty());
            EXPECT_FALSE(with_fields[i].fields.empty());
            EXPECT_EQ(text.events[i].summary, with_fields[i].summary);
            EXPECT_EQ(text.events[i].errors, with_fields[i].errors);
            EXPECT_EQ(text.events[i].start, with_fields[i].start);
            EXPECT_EQ(text.events[i].end, with_fields[i].end);
        }
        EXPECT_EQ(text.events[0].summary, miso ? "MOSI 0xDEADB MISO 0x12345 (20 of 32 bits)"
                                               : "MOSI 0xDEADB (20 of 32 bits)");
    }
}

TEST(Spi, JsonlOutputGetsTheFieldsWithoutSummary) {
    // A sink that reads no summaries (jsonl) gets the same events, fields and errors as
    // one that reads both, without the summary.
    const Waveform w = cutShortThenWhole();
    const auto both = decode(w, {});
    const auto json = test::decodeForFields(w, {DecoderRequest{"spi", {}, {}}});
    ASSERT_EQ(json.size(), 2u);
    ASSERT_EQ(both.size(), 2u);
    for (std::size_t i = 0; i < 2; ++i) {
        EXPECT_EQ(json[i].summary, "");
        EXPECT_NE(both[i].summary, "");
        EXPECT_EQ(eventToJson(json[i], w.timebase), eventToJson(both[i], w.timebase));
    }
    EXPECT_TRUE(json[0].hasError("short_frame"));
}

TEST(Spi, LsbFirstShortFrameKeepsTheBitsInPlace) {
    WaveBuilder wb(Timebase{1, 1'000'000'000}, {"cs", "sclk", "mosi", "miso"},
                   SpiGenerator::idleLevels({1, 1, true, false}));
    SpiGenerator gen(wb, {0, 1, 2, 3}, {1, 1, true, false});
    double t = gen.transfer(1000, {{0xABCD, 0}}, 16, 12);
    auto ev = decode(wb.build(wb.ticksFromNs(t + 1000)), {{"bits", "16"}, {"lsb_first", "1"}});
    ASSERT_EQ(ev.size(), 1u);
    EXPECT_TRUE(ev[0].hasError("short_frame"));
    EXPECT_EQ(u(ev[0], "mosi"), 0xBCDu);
}

TEST(Spi, WithoutCsWordsAreFramedByBitCount) {
    // Two 16-bit transfers decoded as 8-bit words with cs unbound: four words.
    Waveform w = makeSpiCapture({{{0x1234, 0x0102}}, {{0xABCD, 0x0304}}}, 16);
    w.names = {"select_not_named_cs", "sclk", "mosi", "miso"};
    auto ev = decode(w, {{"bits", "8"}});
    ASSERT_EQ(ev.size(), 4u);
    const std::uint64_t want[] = {0x12, 0x34, 0xAB, 0xCD};
    for (int i = 0; i < 4; ++i) {
        EXPECT_EQ(u(ev[i], "mosi"), want[i]);
        EXPECT_EQ(u(ev[i], "miso"), std::uint64_t(i + 1));
        EXPECT_TRUE(ev[i].errors.empty());
    }
    // 12-bit words straddle the transfers: without cs nothing resets the count.
    auto ev12 = decode(w, {{"bits", "12"}});
    ASSERT_EQ(ev12.size(), 3u);
    EXPECT_EQ(u(ev12[0], "mosi"), 0x123u);
    EXPECT_EQ(u(ev12[1], "mosi"), 0x4ABu);
    EXPECT_EQ(u(ev12[2], "mosi"), 0xCDu);  // the capture ends after 8 of 12 bits
    EXPECT_TRUE(ev12[2].hasError("short_frame"));
    EXPECT_EQ(asInt(*ev12[2].get("bits")), 8);
}

TEST(Spi, CaptureEndingMidWordIsShortFrame) {
    WaveBuilder wb(Timebase{1, 1'000'000'000}, {"cs", "sclk", "mosi", "miso"},
                   SpiGenerator::idleLevels({}));
    SpiGenerator gen(wb, {0, 1, 2, 3});
    gen.transfer(1000, {{0xF0F0F0F0, 0}}, 32, 10);
    // Capture ends while cs is still asserted after 10 bits: cut the cs release off.
    Waveform w = wb.build(wb.ticksFromNs(1000 + 200 + 10 * 400));
    std::erase_if(w.edges, [&](const Edge& e) { return e.t > w.end; });
    auto ev = decode(w, {});
    ASSERT_EQ(ev.size(), 1u);
    EXPECT_TRUE(ev[0].hasError("short_frame"));
    EXPECT_EQ(asInt(*ev[0].get("bits")), 10);
    EXPECT_EQ(u(ev[0], "mosi"), 0xF0F0F0F0u >> 22);
}

TEST(Spi, UnboundLineIsNull) {
    Waveform w = makeSpiCapture({{{0x11223344, 0x55667788}}}, 32);
    w.names = {"cs", "sclk", "mosi", "unrelated"};
    auto ev = decode(w, {});
    ASSERT_EQ(ev.size(), 1u);
    EXPECT_EQ(u(ev[0], "mosi"), 0x11223344u);
    EXPECT_TRUE(isNull(*ev[0].get("miso")));
    EXPECT_EQ(ev[0].summary, "MOSI 0x11223344");
}

TEST(Spi, ActiveHighCs) {
    SpiMode mode{0, 0, false, true};
    Waveform w = makeSpiCapture({{{0x5A, 0xA5}}, {{0x3C, 0xC3}}}, 8, mode);
    auto ev =
        decode(w, {{"cpol", "0"}, {"cpha", "0"}, {"bits", "8"}, {"cs_polarity", "active-high"}});
    ASSERT_EQ(ev.size(), 2u);
    EXPECT_EQ(u(ev[0], "mosi"), 0x5Au);
    EXPECT_EQ(u(ev[1], "miso"), 0xC3u);
    // Read with the wrong polarity, the clocks fall outside "selected" time: no words.
    auto wrong = decode(w, {{"cpol", "0"}, {"cpha", "0"}, {"bits", "8"}});
    EXPECT_TRUE(wrong.empty());
}

TEST(Spi, BadOptionsAreInputErrors) {
    Waveform w = makeSpiCapture({{{1, 1}}}, 8);
    EXPECT_THROW(decode(w, {{"bits", "65"}}), InputError);
    EXPECT_THROW(decode(w, {{"bits", "0"}}), InputError);
    EXPECT_THROW(decode(w, {{"cpol", "2"}}), InputError);
    EXPECT_THROW(decode(w, {{"cs_polarity", "sideways"}}), InputError);
}

TEST(Spi, NeedsMosiOrMiso) {
    Waveform w = makeSpiCapture({{{1, 1}}}, 8);
    w.names = {"cs", "sclk", "a", "b"};
    EXPECT_THROW(decode(w, {}), InputError);
}

TEST(Spi, GlitchOnTheClockIsFilteredAndFlagged) {
    // A 5 ns spike on sclk in the middle of bit 10 adds a clock edge pair: without the
    // filter the word shifts by one bit; with glitch_ns=20 the word is right and marked.
    auto build = [] {
        WaveBuilder wb(Timebase{1, 1'000'000'000}, {"cs", "sclk", "mosi", "miso"},
                       SpiGenerator::idleLevels({}));
        SpiGenerator gen(wb, {0, 1, 2, 3});
        gen.transfer(1000, 0xC0FFEE11, 0x12345678, 32);
        Waveform w = wb.build(wb.ticksFromNs(20000));
        // Mode 3: bit k's clock is low from 1200 + 400k to 1400 + 400k; spike inside the low phase.
        const Tick at = 1200 + 400 * 10 + 90;
        w.edges.push_back({at, 1, 1});
        w.edges.push_back({at + 5, 1, 0});
        std::stable_sort(w.edges.begin(), w.edges.end(),
                         [](const Edge& a, const Edge& b) { return a.t < b.t; });
        return w;
    };
    auto raw = decode(build(), {});
    ASSERT_FALSE(raw.empty());
    EXPECT_NE(u(raw[0], "mosi"), 0xC0FFEE11u);
    auto filtered = decode(build(), {{"glitch_ns", "20"}});
    ASSERT_EQ(filtered.size(), 1u);
    EXPECT_EQ(u(filtered[0], "mosi"), 0xC0FFEE11u);
    EXPECT_EQ(u(filtered[0], "miso"), 0x12345678u);
    EXPECT_EQ(filtered[0].errors, std::vector<std::string>{"glitch"});
}
