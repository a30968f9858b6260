// The hint at the end of an SPI decode: when half of the words or more are cut short by
// chip select, all after the same count, the words are that long; an occasional cut word
// gets no hint.
#include <gtest/gtest.h>

#include "capture/capture_reader.h"
#include "core/registry.h"
#include "core/session.h"
#include "spi_generator.h"
#include "spi_info.h"

namespace busdecode {
namespace {

// `transfers` chip-select frames of one `bits`-wide word each; with `cut_one`, the first
// is cut after 5 bits.
std::vector<std::string> adviceFor(int transfers, int bits, const std::string& decode_bits,
                                   bool cut_one = false) {
    Registry::instance().add(makeSpiFactory());
    WaveBuilder wb(Timebase{1, 1'000'000'000}, {"cs", "sclk", "mosi", "miso"},
                   SpiGenerator::idleLevels({}));
    SpiGenerator gen(wb, {0, 1, 2, 3});
    double t = 1000;
    for (int i = 0; i < transfers; ++i)
        t = gen.transfer(t + 1000, {{0xA5u + unsigned(i), 0x5Au}}, bits,
                         cut_one && i == 0 ? 5 : -1);
    const Waveform w = wb.build(wb.ticksFromNs(t + 1000));
    auto reader = memoryReader(w);
    Session session({{"spi", {}, {{"bits", decode_bits}}}}, *reader, "memory");
    session.run();
    return session.facts().advice;
}

// Eight 16-bit words sent in `sent` mode, decoded with cpol/cpha `cpol`, `cpha`.
std::vector<std::string> adviceForMode(SpiMode sent, int cpol, int cpha) {
    Registry::instance().add(makeSpiFactory());
    WaveBuilder wb(Timebase{1, 1'000'000'000}, {"cs", "sclk", "mosi", "miso"},
                   SpiGenerator::idleLevels(sent));
    SpiGenerator gen(wb, {0, 1, 2, 3}, sent);
    double t = 1000;
    for (unsigned i = 0; i < 8; ++i)
        t = gen.transfer(t + 1000, {{0xA5C3u + 977 * i, 0x5A3Cu ^ (131 * i)}}, 16);
    const Waveform w = wb.build(wb.ticksFromNs(t + 1000));
    auto reader = memoryReader(w);
    Session session(
        {{"spi",
          {},
          {{"bits", "16"}, {"cpol", std::to_string(cpol)}, {"cpha", std::to_string(cpha)}}}},
        *reader, "memory");
    session.run();
    return session.facts().advice;
}

}  // namespace

// Data changing right after the edge the given mode samples on: every bit was read as it
// changed. The hint names the mode from the traffic: the shifting edge and the clock's
// rest level at chip select.
TEST(SpiAdvice, AWrongModeIsNamedFromTheTraffic) {
    auto advice = adviceForMode({0, 1}, 0, 0);  // mode 1 traffic read as mode 0
    ASSERT_EQ(advice.size(), 1u);
    EXPECT_NE(advice[0].find("spi: the data lines change after the rising clock edges"),
              std::string::npos)
        << advice[0];
    EXPECT_NE(advice[0].find("and the clock rests low at chip select: the traffic looks SPI "
                             "mode 1 (--opt cpol=0 --opt cpha=1), which samples on the falling "
                             "edge, not cpol=0 cpha=0"),
              std::string::npos)
        << advice[0];
    advice = adviceForMode({1, 0}, 1, 1);  // mode 2 read as mode 3
    ASSERT_EQ(advice.size(), 1u);
    EXPECT_NE(advice[0].find("SPI mode 2 (--opt cpol=1 --opt cpha=0)"), std::string::npos)
        << advice[0];
    advice = adviceForMode({0, 0}, 0, 1);  // mode 0 read as mode 1
    ASSERT_EQ(advice.size(), 1u);
    EXPECT_NE(advice[0].find("SPI mode 0 (--opt cpol=0 --opt cpha=0)"), std::string::npos)
        << advice[0];
}

TEST(SpiAdvice, NoModeHintWhenTheSamplingEdgeIsRight) {
    for (int mode = 0; mode < 4; ++mode)
        EXPECT_TRUE(adviceForMode({mode / 2, mode % 2}, mode / 2, mode % 2).empty()) << mode;
    // Mode 3 read as mode 0 samples on the same (rising) edge: the words are right.
    EXPECT_TRUE(adviceForMode({1, 1}, 0, 0).empty());
}

TEST(SpiAdvice, BytesReadAsLongWordsGetTheirWidth) {
    const auto advice = adviceFor(6, 8, "32");
    ASSERT_EQ(advice.size(), 1u);
    EXPECT_EQ(advice[0],
              "spi: 6 of 6 words were cut short by chip select, each after 8 bits of bits=32: "
              "the words look 8 bits long (--opt bits=8)");
}

TEST(SpiAdvice, NoneWhenTheWidthFitsOrAWordIsCutNowAndThen) {
    EXPECT_TRUE(adviceFor(6, 8, "8").empty());
    EXPECT_TRUE(adviceFor(6, 32, "32", true).empty());  // one word of six cut after 5 bits
    EXPECT_TRUE(adviceFor(1, 8, "32").empty());         // one word: too few to tell
}

}  // namespace busdecode
