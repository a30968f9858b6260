// The committed example captures (captures/tmcl_*) are what the generator makes: they
// decode exactly like the in-memory waveform, and to the traffic the generator sent.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include "core/registry.h"
#include "core/session.h"
#include "support/decode_events.h"
#include "support/paths.h"
#include "tmcl_decoder.h"
#include "tmcl_examples.h"
#include "uart_decoder.h"

namespace busdecode {
namespace {

void registerDecoders() {
    Registry::instance().add(makeUartFactory());
    Registry::instance().add(makeTmclFactory());
}

std::string text(const std::vector<Event>& events) {
    std::string out;
    for (const auto& e : events) {
        out += fmt::format("{} {}", e.type, e.summary);
        for (const auto& err : e.errors)
            out += " !" + err;
        out += "\n";
    }
    return out;
}

TEST(TmclExamples, CommittedCapturesDecodeLikeTheGenerator) {
    registerDecoders();
    for (const auto& ex : tmclExamples()) {
        const auto memory = decodeWaveform(ex.wave, ex.requests);
        const auto file = test::decodeEvents(test::examplePath(ex.file), ex.requests);
        EXPECT_EQ(text(file), text(memory)) << ex.file;
        ASSERT_EQ(file.size(), memory.size());
        for (std::size_t i = 0; i < file.size(); ++i)
            EXPECT_EQ(file[i].start, memory[i].start);
    }
}

TEST(TmclExamples, Rs485SessionReadsAsTheIdeWouldWriteIt) {
    registerDecoders();
    const auto ex = tmclExamples()[0];
    EXPECT_EQ(
        text(decodeWaveform(ex.wave, ex.requests)),
        "command GetVersion 0, 0, 0\n"
        "reply reply 2: GetVersion \"1690V103\"\n"
        "command GAP 71, 0  // Absolute encoder position\n"
        "reply reply 2 <- 1: 100 Successfully executed, no error, GAP value 123456  (rtt 20.750 "
        "ms)\n"
        "command SAP 13, 0, 5  // Commutation mode\n"
        "reply reply 2 <- 1: 100 Successfully executed, no error, SAP value 5  (rtt 20.750 ms)\n"
        "command SAP 94, 0, 2000  // Max velocity\n"
        "reply reply 2 <- 1: 100 Successfully executed, no error, SAP value 2000  (rtt 20.750 ms)\n"
        "command MVP ABS, 0, -90000\n"
        "reply reply 2 <- 1: 100 Successfully executed, no error, MVP value -90000  (rtt 20.750 "
        "ms)\n"
        "command ROL 0, 500\n"
        "reply reply 2 <- 1: 100 Successfully executed, no error, ROL value 500  (rtt 20.750 ms)\n"
        "command SAP 4, 0, 55296  // Motor nominal current  [checksum D2, sum E2] !checksum\n"
        "reply reply 2 <- 1: 1 Wrong checksum, SAP value 51200  (rtt 20.750 ms)\n"
        "command GGP 42, 2  // User variable #42\n"
        "reply reply 2 <- 1: 100 Successfully executed, no error, GGP value -7  (rtt 20.750 ms)\n"
        "command MST 0\n"
        "reply reply 2 <- 1: 100 Successfully executed, no error, MST value 0  (rtt 20.750 ms)\n");
}

TEST(TmclExamples, TwoLineSessionWithUnansweredAndCutCommands) {
    registerDecoders();
    const auto ex = tmclExamples()[1];
    const auto events = decodeWaveform(ex.wave, ex.requests);
    ASSERT_EQ(events.size(), 14u);
    EXPECT_EQ(events[1].summary.substr(0, 20), "reply 2 <- 1: 100 Su");
    EXPECT_EQ(asInt(*events[7].get("value")), 0x10001234);  // UF_CH2 type 1: SPI read
    EXPECT_EQ(std::get<std::string>(*events[10].get("mnemonic")), "RestoreFactorySettings");
    EXPECT_EQ(events[11].errors, std::vector<std::string>{"short_frame"});
    // The reply after the unanswered and the cut command pairs with the last whole one.
    EXPECT_EQ(std::get<std::string>(*events[13].get("request")), "GAP 106, 0  // Actual position");
}

}  // namespace
}  // namespace busdecode
