// The INI text of sigrok and DSView sessions, read once for their three readers: sections,
// comments, blanks and CR line ends; a sigrok session's [device] keys and probe names.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "capture/session_ini.h"

namespace busdecode::test {
namespace {

TEST(SessionIni, GivesEachKeyLineWithItsSectionNumberAndIndent) {
    const std::string text =
        "; a comment\r\n[header]\r\nsamplerate = 1 MHz\r\n\r\n  vDiv0 = 500\n# another\n"
        "[version]\nversion=3\nno value here\n";
    std::vector<std::string> seen;
    forEachIniLine(text, [&](const IniLine& l) {
        seen.push_back(std::string(l.section) + "|" + std::string(l.key) + "|" +
                       std::string(l.value) + "|" + (l.has_value ? "=" : "-") +
                       (l.indented ? "i" : "") + std::to_string(l.number));
    });
    const std::vector<std::string> expected = {"[header]|samplerate|1 MHz|=3",
                                               "[header]|vDiv0|500|=i5", "[version]|version|3|=8",
                                               "[version]|no value here||-9"};
    EXPECT_EQ(seen, expected);
}

TEST(SessionIni, SigrokMetadataKeepsTheDeviceSectionAndNamesDisabledProbes) {
    const SrMetadata meta(
        "[global]\nsigrok version=0.5.2\nprobe9=not a device key\n\n[device 1]\n"
        "samplerate=24 MHz\ntotal probes=4\nprobe1=MA\nprobe3=SL\nunitsize=1\n");
    ASSERT_NE(meta.find("samplerate"), nullptr);
    EXPECT_EQ(*meta.find("samplerate"), "24 MHz");
    EXPECT_EQ(meta.find("sigrok version"), nullptr);
    EXPECT_EQ(meta.number("total probes"), 4);
    EXPECT_EQ(meta.number("absent"), 0);
    EXPECT_EQ(meta.highestProbe(), 3);
    EXPECT_EQ(meta.probeName(0), "MA");
    EXPECT_EQ(meta.probeName(1), "D1");
    EXPECT_EQ(meta.probeName(2), "SL");
}

}  // namespace
}  // namespace busdecode::test
