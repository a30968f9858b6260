// The hint at the end of an SSI decode: every frame short by the same count means words
// of that length (or a lead bit not counted); an occasional short frame gets no hint.
#include <gtest/gtest.h>

#include "capture/capture_reader.h"
#include "core/session.h"
#include "ssi_test_util.h"
#include "support/decode_facts.h"

namespace busdecode {
namespace {

std::vector<std::string> adviceFor(const std::string& capture,
                                   const std::map<std::string, std::string>& options) {
    ssitest::registerSsi();
    return test::decodeCaptureFacts(capture, {"ssi", {}, options}).advice;
}

// A 13-bit encoder clocked `clocks` times per frame (0: one word), decoded with `options`.
std::vector<std::string> adviceForThirteenBits(int clocks,
                                               const std::map<std::string, std::string>& options) {
    ssitest::registerSsi();
    SsiGenConfig cfg;
    cfg.data_bits = 13;
    std::vector<SsiGenFrame> frames;
    for (int i = 0; i < 6; ++i) {
        SsiGenFrame f;
        f.word = 0x1234 + 371 * std::uint64_t(i);
        f.clocks = clocks;
        frames.push_back(f);
    }
    const SsiGenerated g = generateSsi(cfg, frames);
    auto reader = memoryReader(g.wave);
    Session session({{"ssi", {}, options}}, *reader, "memory");
    session.run();
    return session.facts().advice;
}

}  // namespace

// 13-bit words read as 25: a master clocking 14 times gives short frames; one clocking
// 26 times gets the encoder's ring shift (13 bits, a zero, the word again), which looks
// like a whole 25-bit word. Either way the hint says 13. (One of the six words, 0x13A7,
// also repeats a 6-bit pattern by chance: the width is the one most frames agree on.)
TEST(SsiAdvice, ThirteenBitWordsReadAsTwentyFiveGetTheirWidth) {
    auto advice = adviceForThirteenBits(14, {{"bits", "25"}});
    ASSERT_EQ(advice.size(), 1u);
    EXPECT_EQ(advice[0],
              "ssi: every frame ended after 13 bits, short of bits=25: the words look 13 bits "
              "long (--opt bits=13, with st_bits and mt_bits to fit)");
    advice = adviceForThirteenBits(26, {{"bits", "25"}});
    ASSERT_EQ(advice.size(), 1u);
    EXPECT_EQ(advice[0],
              "ssi: every frame repeats a 13-bit word (1 zero bits between, the encoder's ring "
              "shift) within bits=25: the words look 13 bits long (--opt bits=13, with st_bits "
              "and mt_bits to fit)");
    EXPECT_TRUE(adviceForThirteenBits(26, {{"bits", "13"}, {"st_bits", "13"}}).empty());
}

// 13-bit words read as 12: the 13th bit sits where the 0 after a 12-bit word belongs.
// Frames whose last bit is 0 look clean; the hint names the width from those that are 1.
// A master clocking one bit past a word of the right width reads a 0 there: no hint.
TEST(SsiAdvice, AWordOneBitLongerThanBitsIsNamedFromItsLastBits) {
    auto advice = adviceForThirteenBits(14, {{"bits", "12"}, {"st_bits", "12"}});
    ASSERT_EQ(advice.size(), 1u);
    EXPECT_EQ(advice[0],
              "ssi: every frame was clocked 1 bit past bits=12 with no repeat, and in 3 of 6 "
              "frames a 1 came where the 0 after the word belongs: the words look 13 bits long "
              "(--opt bits=13)");
    EXPECT_TRUE(adviceForThirteenBits(15, {{"bits", "13"}, {"st_bits", "13"}}).empty());
}

TEST(SsiAdvice, NoneWhenTheWidthFitsOrOnlySomeFramesAreShort) {
    EXPECT_TRUE(adviceFor("ssi_tmc8100_gray25.vcd", {}).empty());
    // Two of three frames cut short by the master: faults of the traffic.
    EXPECT_TRUE(adviceFor("ssi_singleturn_2mhz.csv", {}).empty());
}

TEST(SsiAdvice, EveryFrameShortNamesTheWidthItHas) {
    auto advice = adviceFor("ssi_tmc8100_gray25.vcd", {{"bits", "28"}});
    ASSERT_EQ(advice.size(), 1u);
    EXPECT_EQ(advice[0],
              "ssi: every frame ended after 25 bits, short of bits=28: the words look 25 bits "
              "long (--opt bits=25)");
    advice = adviceFor("ssi_tmc8100_gray25.vcd", {{"bits", "32"}, {"st_bits", "30"}});
    ASSERT_EQ(advice.size(), 1u);
    EXPECT_NE(advice[0].find("(--opt bits=25, with st_bits and mt_bits to fit)"), std::string::npos)
        << advice[0];
}

TEST(SsiAdvice, OneBitShortSuggestsTheLeadBit) {
    // POSITAL's words carry a bit at the first clock edge: lead=1 counts it.
    const auto advice = adviceFor("ssi_posital_lead.csv", {});
    ASSERT_EQ(advice.size(), 1u);
    EXPECT_NE(advice[0].find("(--opt bits=24; or --opt lead=1, if the level at the first clock "
                             "edge is a bit)"),
              std::string::npos)
        << advice[0];
    EXPECT_TRUE(adviceFor("ssi_posital_lead.csv",
                          {{"bits", "25"}, {"lead", "1"}, {"mt_bits", "12"}, {"st_bits", "12"}})
                    .empty());
}

}  // namespace busdecode
