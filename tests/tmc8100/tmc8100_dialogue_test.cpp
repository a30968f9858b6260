// The application note's exact dialogue ([D1], docs/protocols.md §3.1 / §4.6) on generated signals:
// 0xFE -> "SSI ", 0xFF -> FF 00 01 00, repeated 0x80 reads with Gray positions and
// status flags. Every event is compared exactly (type, ticks, fields, errors).
#include <gtest/gtest.h>

#include "core/gray.h"
#include "core/session.h"
#include "scenario_expect.h"

using namespace busdecode;
using namespace busdecode::test;

namespace {

struct Dialogue {
    Tmc8100Scenario sc;
    std::vector<std::uint16_t> positions = {0x1234, 0x1235, 0xFFFF, 0x0000, 0x8000};
    std::vector<std::uint8_t> flags = {0, 0, 0b010, 0b001, 0b110};
    Dialogue() {
        sc.getProtocol("SSI ");
        sc.getVersion(1, 0);
        for (std::size_t i = 0; i < positions.size(); ++i) {
            Tmc8100Scenario::EncoderRead r;
            r.ssi_word = Tmc8100Scenario::ssiWord(flags[i], std::uint8_t(i * 9), positions[i]);
            sc.readEncoder(r);
            sc.pause(25000);  // the monoflop time before the next SSI read
        }
    }
    // Transfer indices: 0 FE, 1 read; 2 FF, 3 read; then per read k: 4+4k command, +1..+3 replies.
    std::vector<Expected> expected(bool with_ssi) const {
        ScenarioExpect x{sc};
        std::vector<Expected> want = {
            x.command(0, 0xFE, "get_protocol"),
            x.reply(1, "protocol", S("get_protocol"), {{"text", S("SSI ")}}),
            x.command(1, 0x00, "dummy"),
            x.command(2, 0xFF, "get_version"),
            x.reply(3, "version", S("get_version"), {{"major", I(1)}, {"minor", I(0)}}),
            x.command(3, 0x00, "dummy"),
        };
        for (std::size_t k = 0; k < positions.size(); ++k) {
            const std::size_t c = 4 + 4 * k;
            const std::int64_t gray = binaryToGray(positions[k]);
            std::vector<std::pair<std::string, Value>> extra;
            if (with_ssi) extra = {{"ssi_match", Value(true)}, {"encoder_st", I(gray)}};
            want.push_back(x.command(c, 0x80, "read_encoder"));
            want.push_back(x.read(c, c + 3, gray, positions[k], flags[k], true, extra));
            want.push_back(
                x.reply(c + 1, "raw_position", S("read_encoder"), {{"position", I(gray)}}));
            want.push_back(x.command(c + 1, 0x00, "dummy"));
            want.push_back(x.reply(c + 2, "binary_position", S("read_encoder"),
                                   {{"position", I(positions[k])}}));
            want.push_back(x.command(c + 2, 0x00, "dummy"));
            want.push_back(x.reply(c + 3, "flags", S("read_encoder"), {{"flags", I(flags[k])}}));
            want.push_back(x.command(c + 3, 0x00, "dummy"));
        }
        return want;
    }
};

}  // namespace

TEST(Tmc8100Dialogue, SeedDialogueEveryEventExact) {
    registerDecoders();
    Dialogue d;
    // The literal words of the application note: FE 00 00 00 -> 53 53 49 20; FF -> FF 00 01 00.
    ASSERT_EQ(d.sc.transfers()[1].miso, 0x53534920u);
    ASSERT_EQ(d.sc.transfers()[3].miso, 0xFF000100u);
    ASSERT_EQ(d.sc.transfers()[5].miso, 0x10001B2Eu);  // §4.6: ST Gray 0x1B2E = binary 0x1234
    ASSERT_EQ(d.sc.transfers()[6].miso, 0x20001234u);
    ASSERT_EQ(d.sc.transfers()[7].miso, 0x70000000u);
    auto events = decodeWaveform(d.sc.build(), {DecoderRequest{"tmc8100", {}, {}}});
    expectEvents(events, "tmc8100", d.expected(false));
}

TEST(Tmc8100Dialogue, WithoutGpio6TheSameDialogueDecodes) {
    registerDecoders();
    Dialogue d;
    Waveform w = d.sc.build();
    w.names[Tmc8100Scenario::kGpio6] = "unused";
    auto events = decodeWaveform(w, {DecoderRequest{"tmc8100", {}, {}}});
    expectEvents(events, "tmc8100", d.expected(false));
}

TEST(Tmc8100Dialogue, ProtocolOptionFixedToSsiGivesTheSameEvents) {
    registerDecoders();
    Dialogue d;
    auto events = decodeWaveform(
        d.sc.build(), {DecoderRequest{"tmc8100", {}, {{"encoder", "ssi"}, {"mode", "app"}}}});
    expectEvents(events, "tmc8100", d.expected(false));
}

#ifdef BUSDECODE_HAVE_SSI
TEST(Tmc8100Dialogue, SsiDecodedInTheSamePassMatches) {
    registerDecoders();
    Dialogue d;
    auto events = decodeWaveform(
        d.sc.build(), {DecoderRequest{"tmc8100", {}, {}}, DecoderRequest{"ssi", {}, {}}});
    expectEvents(events, "tmc8100", d.expected(true));
    auto frames = only(events, "ssi", "frame");
    ASSERT_EQ(frames.size(), d.positions.size());
    for (std::size_t k = 0; k < frames.size(); ++k)
        EXPECT_EQ(asInt(*frames[k].get("raw")),
                  Tmc8100Scenario::ssiWord(d.flags[k], std::uint8_t(k * 9), d.positions[k]));
}
#endif

TEST(Tmc8100Dialogue, EightBitFramesUnderOneCsAreOneDatagram) {
    // The Landungsbruecke clocks 8-bit frames with cs held for all four: decoded with
    // bits=8 the SPI layer gives bytes, the TMC8100 layer the same datagrams and events.
    registerDecoders();
    Dialogue d;
    auto events = decodeWaveform(d.sc.build(), {DecoderRequest{"tmc8100", {}, {{"bits", "8"}}}});
    expectEvents(events, "tmc8100", d.expected(false));
}

TEST(Tmc8100Dialogue, WithoutMisoOnlyCommandsAndNoFalseErrors) {
    registerDecoders();
    Dialogue d;
    Waveform w = d.sc.build();
    w.names[Tmc8100Scenario::kSdo] = "not_bound";
    auto events = only(decodeWaveform(w, {DecoderRequest{"tmc8100", {}, {}}}), "tmc8100");
    ASSERT_EQ(events.size(), d.sc.transfers().size());
    for (std::size_t i = 0; i < events.size(); ++i) {
        EXPECT_EQ(events[i].type, "command");
        EXPECT_EQ(asInt(*events[i].get("word")), d.sc.transfers()[i].mosi);
        EXPECT_TRUE(events[i].errors.empty()) << events[i].summary;
    }
}
