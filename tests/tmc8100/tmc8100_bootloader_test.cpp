// Bootloader datagrams as the demo scripts send them (docs/protocols.md §3.1, the SSI demo's
// download sequence): every query is sent twice (ask, then read the answer in the next
// transfer), program words are written to consecutive addresses, verified, and the
// program is started, after which the application's command loop answers.
#include <gtest/gtest.h>

#include "core/session.h"
#include "scenario_expect.h"

using namespace busdecode;
using namespace busdecode::test;

namespace {

// 0: W(00) 1: R(00) 2: W(B0) 3: R(B0) 4: W(B8) 5: R(B8) 6..8: writes 9..11: verifies
// 12: start 13: FE 14: read of "SSI ".
Tmc8100Scenario bootSession() {
    Tmc8100Scenario sc;
    sc.transfer(0x00000000u, 0);
    sc.transfer(0x00000000u, 0xB5000000u);  // bootloader version b5 00 00 00
    sc.transfer(0xB0000000u, 0xB5000000u);
    sc.transfer(0xB0000000u, 0x38313030u);  // chip id "8100"
    sc.transfer(0xB8000000u, 0x38313030u);
    sc.transfer(0xB8000000u, 0x11000000u);  // chip revision 0x11
    const std::uint16_t program[] = {0x1234, 0xABCD, 0x0F0F};
    for (int a = 0; a < 3; ++a)
        sc.transfer(0x08000000u | (std::uint32_t(a) << 16) | program[a], 0);
    sc.transfer(0x88000000u, 0);
    sc.transfer(0x88010000u, 0x00001234u);
    sc.transfer(0x88020000u, 0x0000ABCDu);
    sc.transfer(0x10000000u, 0x00000F0Fu);
    sc.getProtocol("SSI ");
    return sc;
}

Expected bootCmd(const ScenarioExpect& x, std::size_t i, int code, const char* name,
                 std::vector<std::pair<std::string, Value>> extra = {}) {
    Expected e = x.command(i, code, name);
    e.fields.insert(e.fields.end(), extra.begin(), extra.end());
    return e;
}

}  // namespace

TEST(Tmc8100Bootloader, ExplicitModeDecodesEveryDatagram) {
    registerDecoders();
    Tmc8100Scenario sc = bootSession();
    auto events =
        decodeWaveform(sc.build(), {DecoderRequest{"tmc8100", {}, {{"mode", "bootloader"}}}});
    ScenarioExpect x{sc};
    expectEvents(
        events, "tmc8100",
        {bootCmd(x, 0, 0x00, "bootloader_version"),
         x.reply(1, "bootloader_version", S("bootloader_version"), {{"version", I(0xB5)}}),
         bootCmd(x, 1, 0x00, "bootloader_version"),
         x.reply(2, "bootloader_version", S("bootloader_version"), {{"version", I(0xB5)}}),
         bootCmd(x, 2, 0xB0, "chip_id"), x.reply(3, "chip_id", S("chip_id"), {{"text", S("8100")}}),
         bootCmd(x, 3, 0xB0, "chip_id"), x.reply(4, "chip_id", S("chip_id"), {{"text", S("8100")}}),
         bootCmd(x, 4, 0xB8, "chip_revision"),
         x.reply(5, "chip_revision", S("chip_revision"), {{"revision", I(0x11)}}),
         bootCmd(x, 5, 0xB8, "chip_revision"),
         // The answer to the second revision query is never read (the next transfer is
         // a program write, whose MISO the bootloader leaves zero here).
         x.reply(6, "chip_revision", S("chip_revision"), {{"revision", I(0)}}),
         bootCmd(x, 6, 0x08, "program_write", {{"address", I(0)}, {"data", I(0x1234)}}),
         bootCmd(x, 7, 0x08, "program_write", {{"address", I(1)}, {"data", I(0xABCD)}}),
         bootCmd(x, 8, 0x08, "program_write", {{"address", I(2)}, {"data", I(0x0F0F)}}),
         bootCmd(x, 9, 0x88, "program_verify", {{"address", I(0)}}),
         x.reply(10, "program_word", S("program_verify"), {{"data", I(0x1234)}, {"address", I(0)}}),
         bootCmd(x, 10, 0x88, "program_verify", {{"address", I(1)}}),
         x.reply(11, "program_word", S("program_verify"), {{"data", I(0xABCD)}, {"address", I(1)}}),
         bootCmd(x, 11, 0x88, "program_verify", {{"address", I(2)}}),
         x.reply(12, "program_word", S("program_verify"), {{"data", I(0x0F0F)}, {"address", I(2)}}),
         bootCmd(x, 12, 0x10, "start_program"),
         // After "start program" the application answers.
         x.command(13, 0xFE, "get_protocol"),
         x.reply(14, "protocol", S("get_protocol"), {{"text", S("SSI ")}}),
         x.command(14, 0x00, "dummy")});
}

TEST(Tmc8100Bootloader, AutoModeDetectsTheBootloaderFromTheChipQueries) {
    registerDecoders();
    Tmc8100Scenario sc = bootSession();
    auto cmds =
        only(decodeWaveform(sc.build(), {DecoderRequest{"tmc8100", {}, {}}}), "tmc8100", "command");
    std::vector<std::string> names;
    for (const auto& e : cmds)
        names.push_back(show(*e.get("name")));
    // Before the chip id query nothing says "bootloader": 00 00 00 00 is the dummy.
    const std::vector<std::string> want = {
        "\"dummy\"",         "\"dummy\"",          "\"chip_id\"",        "\"chip_id\"",
        "\"chip_revision\"", "\"chip_revision\"",  "\"program_write\"",  "\"program_write\"",
        "\"program_write\"", "\"program_verify\"", "\"program_verify\"", "\"program_verify\"",
        "\"start_program\"", "\"get_protocol\"",   "\"dummy\""};
    EXPECT_EQ(names, want);
    for (const auto& e : cmds)
        EXPECT_TRUE(e.errors.empty()) << e.summary;
}

TEST(Tmc8100Bootloader, AutoModeDetectsConsecutiveProgramWrites) {
    registerDecoders();
    Tmc8100Scenario sc;
    for (int a = 0x100; a < 0x103; ++a)
        sc.transfer(0x08000000u | (std::uint32_t(a) << 16) | 0x5555, 0);
    auto cmds =
        only(decodeWaveform(sc.build(), {DecoderRequest{"tmc8100", {}, {}}}), "tmc8100", "command");
    ASSERT_EQ(cmds.size(), 3u);
    // A single 0x09.. word could be anything; the second consecutive address settles it.
    EXPECT_EQ(show(*cmds[0].get("name")), "\"unknown\"");
    EXPECT_EQ(show(*cmds[1].get("name")), "\"program_write\"");
    EXPECT_EQ(show(*cmds[1].get("address")), "257");
    EXPECT_EQ(show(*cmds[2].get("name")), "\"program_write\"");
}
