// The hint at the end of a decode when most characters are garbled: a wrong baud rate,
// character format or polarity; none when the settings fit or faults are few.
#include <gtest/gtest.h>

#include "capture/capture_reader.h"
#include "core/registry.h"
#include "core/session.h"
#include "support/decode_facts.h"
#include "uart_decoder.h"
#include "uart_generator.h"

namespace busdecode {
namespace {

// The advice for captures/uart_rxtx_9600_8n1.vcd (31 characters, 8N1 at 9600 baud)
// decoded with `options`.
std::vector<std::string> adviceWith(const std::map<std::string, std::string>& options) {
    Registry::instance().add(makeUartFactory());
    return test::decodeCaptureFacts("uart_rxtx_9600_8n1.vcd", {"uart", {}, options}).advice;
}

// `n` characters at 1 Mbaud, each with its stop bit low (a framing error), decoded.
std::vector<std::string> adviceForFramingErrors(int n) {
    Registry::instance().add(makeUartFactory());
    UartFormat f;
    f.baud = 1'000'000;
    WaveBuilder wb(Timebase{1, 1'000'000'000}, {"tx"}, {1});
    UartGenerator gen(wb, 0, f);
    UartFaults bad;
    bad.bad_stop = true;
    double t = 2000;
    for (int i = 0; i < n; ++i)
        t = gen.sendChar(t, 0x55, bad) + 5000;
    const Waveform w = wb.build(wb.ticksFromNs(t + 20000));
    auto reader = memoryReader(w);
    Session session({{"uart", {}, {{"baud", "1e6"}}}}, *reader, "memory");
    session.run();
    return session.facts().advice;
}

}  // namespace

TEST(UartAdvice, NoneWhenTheSettingsFit) {
    EXPECT_TRUE(adviceWith({}).empty());
    EXPECT_TRUE(adviceWith({{"baud", "auto"}}).empty());
}

// Read too fast, every character is garbled; the shortest pulses still measure the rate
// the line runs at, and the hint names it.
TEST(UartAdvice, AWrongRateIsMeasuredAndNamed) {
    auto advice = adviceWith({{"baud", "115200"}});
    ASSERT_EQ(advice.size(), 1u);
    EXPECT_EQ(advice[0],
              "uart: the shortest pulses are 104.2 us, a bit at 9600 baud, not at baud=115200 "
              "(105 of 105 characters with framing or parity errors): try --opt baud=9600 (or "
              "baud=auto)");
    // Twice the rate: 15 of 56 characters fail, too few for the format hint; the pulses
    // still say 9600.
    advice = adviceWith({{"baud", "19200"}});
    ASSERT_EQ(advice.size(), 1u);
    EXPECT_NE(advice[0].find("a bit at 9600 baud, not at baud=19200"), std::string::npos)
        << advice[0];
    // Read too slow: a few long characters.
    advice = adviceWith({{"baud", "1200"}});
    ASSERT_EQ(advice.size(), 1u);
    EXPECT_NE(advice[0].find("try --opt baud=9600"), std::string::npos) << advice[0];
}

TEST(UartAdvice, AWrongFormatIsPointedAt) {
    const auto advice = adviceWith({{"parity", "even"}});
    ASSERT_EQ(advice.size(), 1u);
    EXPECT_NE(advice[0].find("21 of 25 characters"), std::string::npos) << advice[0];
    EXPECT_NE(advice[0].find("parity=even"), std::string::npos) << advice[0];
    EXPECT_NE(advice[0].find("check the baud rate (--opt baud=auto measures it)"),
              std::string::npos)
        << advice[0];
}

TEST(UartAdvice, WithAMeasuredRateTheFormatIsPointedAt) {
    const auto advice = adviceWith({{"baud", "auto"}, {"parity", "odd"}});
    ASSERT_EQ(advice.size(), 1u);
    EXPECT_NE(advice[0].find("at baud=9600 as measured (bits=8 parity=odd"), std::string::npos)
        << advice[0];
    EXPECT_EQ(advice[0].find("baud=auto"), std::string::npos) << advice[0];
}

TEST(UartAdvice, EightCharactersAreEnoughToTell) {
    EXPECT_TRUE(adviceForFramingErrors(7).empty());
    const auto advice = adviceForFramingErrors(8);
    ASSERT_EQ(advice.size(), 1u);
    EXPECT_EQ(advice[0].rfind("uart: 8 of 8 characters", 0), 0u) << advice[0];
}

}  // namespace busdecode
