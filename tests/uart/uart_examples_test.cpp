// The committed example captures (captures/uart_*) are what the generator makes: they
// decode exactly like the in-memory waveform, and to the truth the generator sent.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include "core/registry.h"
#include "core/session.h"
#include "support/decode_events.h"
#include "support/paths.h"
#include "uart_decoder.h"
#include "uart_examples.h"

namespace busdecode {
namespace {

std::string text(const std::vector<Event>& events) {
    std::string out;
    for (const auto& e : events) {
        out += fmt::format("{} {} {}", e.start, e.type, e.summary);
        for (const auto& err : e.errors)
            out += " !" + err;
        out += "\n";
    }
    return out;
}

TEST(UartExamples, CommittedCapturesDecodeLikeTheGenerator) {
    Registry::instance().add(makeUartFactory());
    const auto examples = uartExamples();
    ASSERT_EQ(examples.size(), 2u);
    for (const auto& ex : examples) {
        const auto memory = decodeWaveform(ex.wave, ex.requests);
        const auto file = test::decodeEvents(test::examplePath(ex.file), ex.requests);
        EXPECT_EQ(text(file), text(memory)) << ex.file;
    }
}

TEST(UartExamples, TheyCarryWhatWasSent) {
    Registry::instance().add(makeUartFactory());
    const auto examples = uartExamples();
    std::string rx, tx;
    for (const auto& e : decodeWaveform(examples[0].wave, examples[0].requests)) {
        ASSERT_TRUE(e.errors.empty()) << e.summary;
        (std::get<std::string>(*e.get("line")) == "rx" ? rx : tx) += char(asInt(*e.get("value")));
    }
    EXPECT_EQ(tx, "AT+VERSION?\r\n");
    EXPECT_EQ(rx, "+VERSION:1.0\r\nOK\r\n");

    EXPECT_EQ(text(decodeWaveform(examples[1].wave, examples[1].requests)),
              "25 byte tx 0x48 'H'\n"
              "160 byte tx 0x69 'i'\n"
              "295 byte tx 0x21 '!'\n"
              "451 byte tx 0x50 'P' !parity\n"
              "606 byte tx 0x46 'F' !framing\n"
              "761 byte tx 0x00 !framing\n"
              "761 break tx break (38 bit times)\n"
              "1311 byte tx 0x6F 'o'\n"
              "1441 byte tx 0x6B 'k'\n");
}

}  // namespace
}  // namespace busdecode
