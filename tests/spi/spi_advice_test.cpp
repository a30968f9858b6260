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

}  // namespace

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
