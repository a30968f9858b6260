// A real capture through the TMC8100 layer: the ADF4351 register writes
// (sigrok-dumps spi/adf4351/set-4000mhz.sr, 32-bit words, mode 0) are not TMC8100
// traffic. The SPI layer must give sigrok's words; the TMC8100 layer must report them as
// unknown commands without inventing replies, reads or a bootloader session.
#include <gtest/gtest.h>

#include "capture/capture_reader.h"
#include "core/session.h"
#include "event_expect.h"
#include "support/decode_events.h"
#include "support/paths.h"

using namespace busdecode;
using namespace busdecode::test;

namespace {
std::vector<Event> decodeFile(const std::string& path, std::vector<DecoderRequest> req) {
    registerDecoders();
    return test::decodeEvents(path, std::move(req));
}
}  // namespace

TEST(Tmc8100Capture, Adf4351WordsAreUnknownCommands) {
    const std::string path = realCaptures() + "/sigrok-dumps/spi/adf4351/set-4000mhz.sr";
    // Channels: CS# 0, MOSI 1, CLK 2; no MISO line.
    std::map<std::string, std::string> map = {{"cs", "0"}, {"mosi", "1"}, {"sclk", "2"}};
    std::map<std::string, std::string> opts = {{"cpol", "0"}, {"cpha", "0"}};
    auto spi = only(decodeFile(path, {DecoderRequest{"spi", map, opts}}), "spi");
    auto tmc = decodeFile(path, {DecoderRequest{"tmc8100", map, opts}});

    const std::uint32_t words[] = {0x00D80005, 0x008C80FC, 0x000004B3,
                                   0x00004E42, 0x08008011, 0x00500000};
    ASSERT_EQ(spi.size(), 6u);
    auto cmds = only(tmc, "tmc8100");
    ASSERT_EQ(cmds.size(), 6u) << "only commands: no replies, reads or GPIO6 events";
    for (int i = 0; i < 6; ++i) {
        SCOPED_TRACE(i);
        EXPECT_EQ(std::uint64_t(asInt(*spi[i].get("mosi"))), words[i]);
        EXPECT_TRUE(isNull(*spi[i].get("miso")));
        EXPECT_EQ(cmds[i].type, "command");
        EXPECT_EQ(show(*cmds[i].get("name")), "\"unknown\"");
        EXPECT_EQ(asInt(*cmds[i].get("code")), words[i] >> 24);
        EXPECT_EQ(std::uint64_t(asInt(*cmds[i].get("word"))), words[i]);
        EXPECT_EQ(cmds[i].start, spi[i].start);
        EXPECT_EQ(cmds[i].end, spi[i].end);
        EXPECT_TRUE(cmds[i].errors.empty());
    }
}
