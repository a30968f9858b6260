// The hint at the end of an SSI decode: every frame short by the same count means words
// of that length (or a lead bit not counted); an occasional short frame gets no hint.
#include <gtest/gtest.h>

#include "ssi_test_util.h"
#include "support/decode_facts.h"

namespace busdecode {
namespace {

std::vector<std::string> adviceFor(const std::string& capture,
                                   const std::map<std::string, std::string>& options) {
    ssitest::registerSsi();
    return test::decodeCaptureFacts(capture, {"ssi", {}, options}).advice;
}

}  // namespace

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
