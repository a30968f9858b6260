// TMCL passes on the hint of the UART it is stacked on: a wrong rate garbles every
// datagram, and the UART's hint says what to check.
#include <gtest/gtest.h>

#include "core/registry.h"
#include "support/decode_facts.h"
#include "tmcl_decoder.h"
#include "uart_decoder.h"

namespace busdecode {
namespace {

std::vector<std::string> adviceWith(const std::map<std::string, std::string>& options) {
    Registry::instance().add(makeUartFactory());
    Registry::instance().add(makeTmclFactory());
    return test::decodeCaptureFacts("tmcl_rs485_9600.vcd", {"tmcl", {}, options}).advice;
}

}  // namespace

TEST(TmclAdvice, TheUartsHintComesThrough) {
    EXPECT_TRUE(adviceWith({}).empty());
    const auto advice = adviceWith({{"baud", "115200"}});
    ASSERT_EQ(advice.size(), 1u);
    EXPECT_EQ(advice[0].rfind("tmcl: its UART: ", 0), 0u) << advice[0];
    EXPECT_NE(advice[0].find("a bit at 9600 baud, not at baud=115200"), std::string::npos)
        << advice[0];
}

// Read too slow, the bus gives a few long garbled characters: datagrams cut short, not
// enough characters for a hint about errors; the pulses still measure the rate.
TEST(TmclAdvice, DatagramsCutShortAtTooSlowARateGetTheRate) {
    const auto advice = adviceWith({{"baud", "2400"}});
    ASSERT_EQ(advice.size(), 1u);
    EXPECT_NE(advice[0].find("tmcl: its UART: the shortest pulses are 104.2 us, a bit at 9600 "
                             "baud, not at baud=2400"),
              std::string::npos)
        << advice[0];
    EXPECT_NE(advice[0].find("try --opt baud=9600"), std::string::npos) << advice[0];
}

}  // namespace busdecode
