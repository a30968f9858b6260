// UART decoder on generated traffic with known truth: every format, both lines, faults,
// breaks, clock error, auto baud.
#include <gtest/gtest.h>

#include <random>

#include <fmt/format.h>

#include "core/registry.h"
#include "core/session.h"
#include "sinks/event_format.h"
#include "support/decode_events.h"
#include "uart_decoder.h"
#include "uart_generator.h"

namespace busdecode {
namespace {

class UartTest : public ::testing::Test {
protected:
    static void SetUpTestSuite() { Registry::instance().add(makeUartFactory()); }
};

std::vector<std::uint32_t> randomValues(std::mt19937& rng, int n, int bits) {
    std::uniform_int_distribution<std::uint32_t> d(0, (1u << bits) - 1);
    std::vector<std::uint32_t> v;
    for (int i = 0; i < n; ++i)
        v.push_back(d(rng));
    return v;
}

std::map<std::string, std::string> optionsFor(const UartFormat& f) {
    static const char* kParity[] = {"none", "even", "odd", "mark", "space", "ignore"};
    return {{"baud", fmt::format("{:g}", f.baud)}, {"bits", std::to_string(f.bits)},
            {"parity", kParity[int(f.parity)]},    {"stop", fmt::format("{:g}", f.stop_bits)},
            {"invert", f.invert ? "1" : "0"},      {"lsb_first", f.lsb_first ? "1" : "0"}};
}

TEST_F(UartTest, EveryFormatRoundTrips) {
    std::mt19937 rng(1234);
    int checked = 0;
    for (int bits = 5; bits <= 9; ++bits)
        for (Parity p : {Parity::None, Parity::Even, Parity::Odd, Parity::Mark, Parity::Space})
            for (double stop : {1.0, 1.5, 2.0})
                for (bool invert : {false, true}) {
                    UartFormat f;
                    f.baud = 115200;
                    f.bits = bits;
                    f.parity = p;
                    f.stop_bits = stop;
                    f.invert = invert;
                    WaveBuilder wb(Timebase{1, 1'000'000'000}, {"tx"}, {std::uint8_t(!invert)});
                    UartGenerator gen(wb, 0, f);
                    const auto values = randomValues(rng, 40, bits);
                    const double end = gen.sendChars(5000, values);
                    auto events = decodeWaveform(wb.build(wb.ticksFromNs(end + 100000)),
                                                 {{"uart", {}, optionsFor(f)}});
                    auto bytes = test::eventsOfType(events, "byte");
                    ASSERT_EQ(bytes.size(), values.size()) << bits << " bits, stop " << stop;
                    for (std::size_t i = 0; i < values.size(); ++i) {
                        EXPECT_EQ(asInt(*bytes[i].get("value")), values[i]);
                        EXPECT_TRUE(bytes[i].errors.empty()) << bytes[i].summary;
                        EXPECT_EQ(std::get<std::string>(*bytes[i].get("line")), "tx");
                    }
                    ++checked;
                }
    EXPECT_EQ(checked, 5 * 5 * 3 * 2);
}

TEST_F(UartTest, BothLinesOverlappingInTimeOrder) {
    std::mt19937 rng(7);
    UartFormat f;
    f.baud = 9600;
    WaveBuilder wb(Timebase{1, 1'000'000'000}, {"rx", "tx"}, {1, 1});
    UartGenerator rx(wb, 0, f), tx(wb, 1, f);
    const auto rv = randomValues(rng, 30, 8), tv = randomValues(rng, 30, 8);
    rx.sendChars(1000, rv, 3000);
    const double end = tx.sendChars(1000 + 0.37 * rx.bitNs(), tv, 5000);
    auto events = test::eventsOfType(
        decodeWaveform(wb.build(wb.ticksFromNs(end + 1e6)), {{"uart", {}, {}}}), "byte");
    std::vector<std::uint32_t> got_rx, got_tx;
    Tick last = kNoTick;
    for (const auto& e : events) {
        EXPECT_GE(e.start, last);
        last = e.start;
        (std::get<std::string>(*e.get("line")) == "rx" ? got_rx : got_tx)
            .push_back(std::uint32_t(asInt(*e.get("value"))));
    }
    EXPECT_EQ(got_rx, rv);
    EXPECT_EQ(got_tx, tv);
}

TEST_F(UartTest, EventSpansStartEdgeToEndOfStopBit) {
    UartFormat f;
    f.baud = 1'000'000;  // 1000 ns per bit: exact ticks
    WaveBuilder wb(Timebase{1, 1'000'000'000}, {"tx"}, {1});
    UartGenerator gen(wb, 0, f);
    gen.sendChar(2000, 0xA5);
    auto bytes = test::eventsOfType(
        decodeWaveform(wb.build(30000), {{"uart", {}, {{"baud", "1e6"}}}}), "byte");
    ASSERT_EQ(bytes.size(), 1u);
    EXPECT_EQ(bytes[0].start, 2000);
    EXPECT_EQ(bytes[0].end, 12000);
    EXPECT_EQ(asInt(*bytes[0].get("value")), 0xA5);
}

TEST_F(UartTest, JsonlOutputGetsTheFieldsWithoutSummary) {
    // A sink that reads no summaries (jsonl, Python) gets the same bytes, fields and
    // errors, without the summary that text output prints.
    UartFormat f;
    f.baud = 1'000'000;
    WaveBuilder wb(Timebase{1, 1'000'000'000}, {"tx"}, {1});
    UartGenerator gen(wb, 0, f);
    double t = gen.sendChar(2000, 'A');
    t = gen.sendChar(t + 1000, 0x7E, {.bad_stop = true});
    const Waveform w = wb.build(wb.ticksFromNs(t + 30000));
    const std::vector<DecoderRequest> uart = {{"uart", {}, {{"baud", "1e6"}}}};
    const auto both = test::eventsOfType(decodeWaveform(w, uart), "byte");
    const auto json = test::eventsOfType(test::decodeForFields(w, uart), "byte");
    ASSERT_EQ(both.size(), 2u);
    ASSERT_EQ(json.size(), 2u);
    for (std::size_t i = 0; i < 2; ++i) {
        EXPECT_EQ(json[i].summary, "");
        EXPECT_EQ(eventToJson(json[i], w.timebase), eventToJson(both[i], w.timebase));
    }
    EXPECT_EQ(both[0].summary, "tx 0x41 'A'");
    EXPECT_EQ(json[1].errors, std::vector<std::string>{"framing"});
}

TEST_F(UartTest, ParityAndFramingErrors) {
    UartFormat f;
    f.baud = 19200;
    f.parity = Parity::Even;
    WaveBuilder wb(Timebase{1, 1'000'000'000}, {"rx"}, {1});
    UartGenerator gen(wb, 0, f);
    double t = gen.sendChar(1000, 0x31);
    t = gen.sendChar(t + 1000, 0x32, {.bad_parity = true});
    t = gen.sendChar(t + 1000, 0x33, {.bad_stop = true});
    t = gen.sendChar(t + 1e5, 0x34);
    auto bytes =
        test::eventsOfType(decodeWaveform(wb.build(wb.ticksFromNs(t + 1e6)),
                                          {{"uart", {}, {{"baud", "19200"}, {"parity", "even"}}}}),
                           "byte");
    ASSERT_EQ(bytes.size(), 4u);
    EXPECT_TRUE(bytes[0].errors.empty());
    EXPECT_EQ(bytes[1].errors, std::vector<std::string>{"parity"});
    EXPECT_EQ(std::get<bool>(*bytes[1].get("parity_ok")), false);
    EXPECT_EQ(bytes[2].errors, std::vector<std::string>{"framing"});
    EXPECT_EQ(asInt(*bytes[2].get("value")), 0x33);
    EXPECT_TRUE(bytes[3].errors.empty());
    EXPECT_EQ(asInt(*bytes[3].get("value")), 0x34);
}

TEST_F(UartTest, BreakIsReportedWithItsLength) {
    UartFormat f;
    f.baud = 9600;
    WaveBuilder wb(Timebase{1, 1'000'000'000}, {"tx"}, {1});
    UartGenerator gen(wb, 0, f);
    double t = gen.sendChar(1000, 'A');
    t = gen.sendBreak(t + 10000, 30 * gen.bitNs());
    t = gen.sendChar(t + 2 * gen.bitNs(), 'B');
    auto events = decodeWaveform(wb.build(wb.ticksFromNs(t + 1e6)), {{"uart", {}, {}}});
    auto bytes = test::eventsOfType(events, "byte");
    auto breaks = test::eventsOfType(events, "break");
    ASSERT_EQ(bytes.size(), 3u);
    EXPECT_EQ(asInt(*bytes[1].get("value")), 0);
    EXPECT_TRUE(bytes[1].hasError("framing"));
    EXPECT_EQ(asInt(*bytes[2].get("value")), 'B');
    ASSERT_EQ(breaks.size(), 1u);
    EXPECT_NEAR(double(asInt(*breaks[0].get("duration_ns"))), 30 * gen.bitNs(), 1);
}

TEST_F(UartTest, NoBreakForLessThanAWholeFrame) {
    // 8N1: a frame is 10 bit times. Low for 9.51..9.99 of them covers the stop bit's
    // sample (a framing error) but not the frame: no break; from 10 on, a break.
    for (double bits : {9.51, 9.6, 9.99, 10.0, 10.5}) {
        SCOPED_TRACE(bits);
        UartFormat f;
        f.baud = 9600;
        WaveBuilder wb(Timebase{1, 1'000'000'000}, {"tx"}, {1});
        UartGenerator gen(wb, 0, f);
        double t = gen.sendChar(1000, 'A');
        t = gen.sendBreak(t + 10000, bits * gen.bitNs());
        t = gen.sendChar(t + 2 * gen.bitNs(), 'B');
        auto events = decodeWaveform(wb.build(wb.ticksFromNs(t + 1e6)), {{"uart", {}, {}}});
        auto bytes = test::eventsOfType(events, "byte");
        ASSERT_EQ(bytes.size(), 3u);
        EXPECT_TRUE(bytes[1].hasError("framing"));
        EXPECT_EQ(asInt(*bytes[2].get("value")), 'B');
        EXPECT_EQ(test::eventsOfType(events, "break").size(), bits >= 10 ? 1u : 0u);
    }
}

TEST_F(UartTest, ToleratesTransmitterClockError) {
    std::mt19937 rng(99);
    for (double err : {-0.03, 0.03}) {
        UartFormat f;
        f.baud = 57600;
        WaveBuilder wb(Timebase{1, 1'000'000'000}, {"tx"}, {1});
        UartGenerator gen(wb, 0, f);
        const auto values = randomValues(rng, 50, 8);
        double t = 500;
        for (auto v : values)
            t = gen.sendChar(t, v, {.rate_error = err});
        auto bytes = test::eventsOfType(
            decodeWaveform(wb.build(wb.ticksFromNs(t + 1e5)), {{"uart", {}, {{"baud", "57600"}}}}),
            "byte");
        ASSERT_EQ(bytes.size(), values.size());
        for (std::size_t i = 0; i < values.size(); ++i)
            EXPECT_EQ(asInt(*bytes[i].get("value")), values[i]);
    }
}

TEST_F(UartTest, AutoBaudFindsTheRateFromTheShortestPulse) {
    std::mt19937 rng(5);
    for (double baud : {9600.0, 115200.0, 1e6}) {
        UartFormat f;
        f.baud = baud;
        // A sampled capture (10 MHz), like a logic analyser's.
        WaveBuilder wb(Timebase{1, 10'000'000}, {"rx"}, {1});
        UartGenerator gen(wb, 0, f);
        const auto values = randomValues(rng, 200, 8);
        const double end = gen.sendChars(3000, values, 2 * gen.bitNs());
        auto events =
            decodeWaveform(wb.build(wb.ticksFromNs(end + 1e6)), {{"uart", {}, {{"baud", "auto"}}}});
        auto bauds = test::eventsOfType(events, "baud");
        ASSERT_EQ(bauds.size(), 1u);
        EXPECT_DOUBLE_EQ(asDouble(*bauds[0].get("baud")), baud);
        auto bytes = test::eventsOfType(events, "byte");
        ASSERT_EQ(bytes.size(), values.size()) << baud;
        for (std::size_t i = 0; i < values.size(); ++i)
            EXPECT_EQ(asInt(*bytes[i].get("value")), values[i]);
    }
}

TEST_F(UartTest, AutoBaudIsNotSlowedByGapsShorterThanABit) {
    // 3 us between characters at 57600 baud (a bit is 17.4 us): the stop bit and the gap
    // are one high pulse within a quarter bit of a whole bit, but not a bit long.
    std::mt19937 rng(7);
    for (bool invert : {false, true}) {
        UartFormat f;
        f.baud = 57600;
        f.invert = invert;
        WaveBuilder wb(Timebase{1, 1'000'000'000}, {"rx"}, {std::uint8_t(!invert)});
        UartGenerator gen(wb, 0, f);
        const double end = gen.sendChars(5000, randomValues(rng, 100, 8), 3000);
        auto o = optionsFor(f);
        o["baud"] = "auto";
        auto bauds = test::eventsOfType(
            decodeWaveform(wb.build(wb.ticksFromNs(end + 1e5)), {{"uart", {}, o}}), "baud");
        ASSERT_EQ(bauds.size(), 1u);
        EXPECT_NEAR(asDouble(*bauds[0].get("measured_baud")), 57600, 57600 * 0.001) << invert;
    }
}

TEST_F(UartTest, AutoBaudOnAShortCaptureDecidesAtTheEnd) {
    UartFormat f;
    f.baud = 38400;
    WaveBuilder wb(Timebase{1, 1'000'000'000}, {"tx"}, {1});
    UartGenerator gen(wb, 0, f);
    const double end = gen.sendChars(1000, {'U', 'h', 'i'});
    auto events =
        decodeWaveform(wb.build(wb.ticksFromNs(end + 1e5)), {{"uart", {}, {{"baud", "auto"}}}});
    auto bytes = test::eventsOfType(events, "byte");
    ASSERT_EQ(bytes.size(), 3u);
    EXPECT_EQ(asInt(*bytes[2].get("value")), 'i');
}

TEST_F(UartTest, CharacterCutShortByTheCaptureEnd) {
    UartFormat f;
    f.baud = 9600;
    WaveBuilder wb(Timebase{1, 1'000'000'000}, {"tx"}, {1});
    UartGenerator gen(wb, 0, f);
    const double t = gen.sendChar(1000, 'x');
    gen.sendChar(t, 'y');
    auto bytes = test::eventsOfType(
        decodeWaveform(wb.build(wb.ticksFromNs(t + 4 * gen.bitNs())), {{"uart", {}, {}}}), "byte");
    ASSERT_EQ(bytes.size(), 2u);
    EXPECT_EQ(asInt(*bytes[0].get("value")), 'x');
    EXPECT_TRUE(bytes[1].hasError("short_frame"));
    EXPECT_TRUE(isNull(*bytes[1].get("value")));
}

TEST_F(UartTest, GlitchShorterThanHalfABitIsNoCharacter) {
    UartFormat f;
    f.baud = 9600;
    WaveBuilder wb(Timebase{1, 1'000'000'000}, {"tx"}, {1});
    UartGenerator gen(wb, 0, f);
    wb.setNs(0, 1000, false);
    wb.setNs(0, 1000 + 0.3 * gen.bitNs(), true);
    const double end = gen.sendChar(5 * gen.bitNs(), 'k');
    auto bytes = test::eventsOfType(
        decodeWaveform(wb.build(wb.ticksFromNs(end + 1e5)), {{"uart", {}, {}}}), "byte");
    ASSERT_EQ(bytes.size(), 1u);
    EXPECT_EQ(asInt(*bytes[0].get("value")), 'k');
}

TEST_F(UartTest, MsbFirstBitOrder) {
    UartFormat f;
    f.baud = 9600;
    f.lsb_first = false;
    WaveBuilder wb(Timebase{1, 1'000'000'000}, {"tx"}, {1});
    UartGenerator gen(wb, 0, f);
    const double end = gen.sendChars(1000, {0x01, 0x80, 0x3C});
    auto bytes = test::eventsOfType(
        decodeWaveform(wb.build(wb.ticksFromNs(end + 1e5)), {{"uart", {}, {{"lsb_first", "0"}}}}),
        "byte");
    ASSERT_EQ(bytes.size(), 3u);
    EXPECT_EQ(asInt(*bytes[0].get("value")), 0x01);
    EXPECT_EQ(asInt(*bytes[1].get("value")), 0x80);
    EXPECT_EQ(asInt(*bytes[2].get("value")), 0x3C);
}

TEST_F(UartTest, BadOptionsAreRejectedWithTheValidChoices) {
    WaveBuilder wb(Timebase{1, 1'000'000'000}, {"tx"}, {1});
    auto w = wb.build(100);
    try {
        decodeWaveform(w, {{"uart", {}, {{"bits", "10"}}}});
        FAIL() << "bits=10 accepted";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("from 5 to 9"), std::string::npos) << e.what();
    }
    EXPECT_THROW(decodeWaveform(w, {{"uart", {}, {{"parity", "sometimes"}}}}), InputError);
    WaveBuilder none(Timebase{1, 1'000'000'000}, {"clk"}, {1});
    EXPECT_THROW(decodeWaveform(none.build(100), {{"uart", {}, {}}}), InputError);
}

TEST_F(UartTest, GlitchFilterRemovesASpikeAtTheSamplePoint) {
    UartFormat f;
    f.baud = 9600;
    WaveBuilder wb(Timebase{1, 1'000'000'000}, {"tx"}, {1});
    UartGenerator gen(wb, 0, f);
    // 0x00: every data bit low; a 300 ns spike high right at the middle of bit 3.
    gen.sendChar(1000, 0x00);
    WaveBuilder spiked(Timebase{1, 1'000'000'000}, {"tx"}, {1});
    const double bit = gen.bitNs();
    spiked.setNs(0, 1000, false);
    spiked.setNs(0, 1000 + 4.5 * bit - 150, true);
    spiked.setNs(0, 1000 + 4.5 * bit + 150, false);
    spiked.setNs(0, 1000 + 9 * bit, true);
    const auto w = spiked.build(spiked.ticksFromNs(1e6));
    auto raw = test::eventsOfType(decodeWaveform(w, {{"uart", {}, {}}}), "byte");
    ASSERT_EQ(raw.size(), 1u);
    EXPECT_EQ(asInt(*raw[0].get("value")), 0x08);
    auto filtered =
        test::eventsOfType(decodeWaveform(w, {{"uart", {}, {{"glitch_ns", "500"}}}}), "byte");
    ASSERT_EQ(filtered.size(), 1u);
    EXPECT_EQ(asInt(*filtered[0].get("value")), 0x00);
}

TEST_F(UartTest, AutoBaudIsNotFooledByGlitches) {
    std::mt19937 rng(11);
    UartFormat f;
    f.baud = 57600;
    WaveBuilder wb(Timebase{1, 1'000'000'000}, {"rx"}, {1});
    UartGenerator gen(wb, 0, f);
    // Three 40 ns spikes on the idle line first, then traffic.
    for (int i = 0; i < 3; ++i) {
        wb.setNs(0, 1000 + i * 5000, false);
        wb.setNs(0, 1040 + i * 5000, true);
    }
    const auto values = randomValues(rng, 100, 8);
    const double end = gen.sendChars(50000, values, gen.bitNs());
    auto events =
        decodeWaveform(wb.build(wb.ticksFromNs(end + 1e5)), {{"uart", {}, {{"baud", "auto"}}}});
    auto bauds = test::eventsOfType(events, "baud");
    ASSERT_EQ(bauds.size(), 1u);
    EXPECT_DOUBLE_EQ(asDouble(*bauds[0].get("baud")), 57600);
    std::vector<std::uint32_t> got;
    for (const auto& e : test::eventsOfType(events, "byte"))
        if (e.errors.empty()) got.push_back(std::uint32_t(asInt(*e.get("value"))));
    EXPECT_EQ(got, values);  // the spikes are too short to pass the start-bit check
}

}  // namespace
}  // namespace busdecode
