// The `decode` command (with the spi, tmc8100 and ssi plugins) on the example captures:
// JSON lines carry the contract's fields, ssi_match comes from the ssi decoder in the
// same pass, and the spi decoder alone gives the datagrams.
#include <gtest/gtest.h>

#include <sstream>

#include "support/paths.h"

namespace busdecode {
namespace {

std::string capture(const std::string& name) {
    return test::sourceDir() + "/captures/" + name;
}

std::vector<std::string> linesWith(const std::string& out, const std::string& what) {
    std::vector<std::string> v;
    std::istringstream in(out);
    std::string line;
    while (std::getline(in, line))
        if (line.find(what) != std::string::npos) v.push_back(line);
    return v;
}

TEST(Tmc8100Cli, DialogueJsonLinesWithSsiInTheSamePass) {
    const auto r = test::runDecode({capture("tmc8100_ssi_dialogue.vcd"), "--proto", "tmc8100",
                                    "--proto", "ssi", "--opt", "ssi.gray=1", "--format", "jsonl"});
    ASSERT_EQ(r.status, 0) << r.err;
    const auto reads = linesWith(r.out, "\"type\":\"encoder_read\"");
    ASSERT_EQ(reads.size(), 6u) << r.out;
    EXPECT_NE(
        reads[0].find(
            "\"gray\":6958,\"binary\":4660,\"flags\":0,\"consistent\":true,\"ssi_match\":true"),
        std::string::npos)
        << reads[0];
    for (const auto& l : reads)
        EXPECT_NE(l.find("\"ssi_match\":true"), std::string::npos) << l;
    const auto replies = linesWith(r.out, "\"type\":\"reply\"");
    ASSERT_EQ(replies.size(), 2u + 6u * 3u);
    EXPECT_NE(replies[0].find("\"tag\":83,\"value\":5458208,\"meaning\":\"protocol\""),
              std::string::npos)
        << replies[0];
    EXPECT_NE(replies[1].find("\"tag\":255,\"value\":256,\"meaning\":\"version\""),
              std::string::npos)
        << replies[1];
    const auto commands = linesWith(r.out, "\"type\":\"command\"");
    ASSERT_EQ(commands.size(), 2u * 2u + 6u * 4u);
    EXPECT_NE(commands[0].find("\"code\":254,\"name\":\"get_protocol\""), std::string::npos)
        << commands[0];
    EXPECT_TRUE(linesWith(r.out, "\"errors\":[\"").empty()) << "no faults in the dialogue";
}

TEST(Tmc8100Cli, FaultsAreReported) {
    const auto r =
        test::runDecode({capture("tmc8100_faults.vcd"), "--proto", "tmc8100", "--proto", "ssi"});
    ASSERT_EQ(r.status, 0) << r.err;
    for (const char* fault :
         {"inconsistent", "ssi_mismatch", "avail_low", "unexpected_avail", "replies_pending"})
        EXPECT_NE(r.out.find(fault), std::string::npos) << fault << "\n" << r.out;
}

TEST(Tmc8100Cli, SpiAloneGivesTheDatagrams) {
    const auto r = test::runDecode({capture("tmc8100_ssi_dialogue.vcd"), "--proto", "spi", "--map",
                                    "cs=spi_csn", "--format", "jsonl"});
    ASSERT_EQ(r.status, 0) << r.err;
    const auto words = linesWith(r.out, "\"type\":\"transfer\"");
    ASSERT_EQ(words.size(), 28u);
    EXPECT_NE(words[0].find("\"mosi\":4261412864,\"miso\":0,\"bits\":32"), std::string::npos)
        << words[0];
    EXPECT_NE(words[1].find("\"mosi\":0,\"miso\":1397967136,\"bits\":32"), std::string::npos)
        << words[1];
}

TEST(Tmc8100Cli, ListShowsRolesAndOptions) {
    const auto r = test::runDecode({"--list"});
    ASSERT_EQ(r.status, 0) << r.err;
    for (const char* s : {"tmc8100", "avail", "gpio6", "mode", "encoder", "cpol", "cs_polarity"})
        EXPECT_NE(r.out.find(s), std::string::npos) << s;
}

}  // namespace
}  // namespace busdecode
