// `decode --formats`: every reader listed with what it recognises; with a capture, what
// it is, DSView's decoder settings included so they can be copied.
#include <gtest/gtest.h>

#include "capture/format_list.h"
#include "support/paths.h"

namespace busdecode::test {
namespace {

TEST(FormatsCli, ListsEveryReader) {
    const auto r = runDecode({"--formats"});
    ASSERT_EQ(r.status, 0) << r.err;
    for (const auto& f : captureFormats())
        EXPECT_NE(r.out.find(f.name), std::string::npos) << f.name;
    for (const char* name :
         {"vcd", "fst", "saleae-bin", "saleae-bin-analog", "sigrok-sr", "dsview-dsl",
          "vivado-ila-csv", "sample-list", "gzip", "xz", "zstd", ".sal"})
        EXPECT_NE(r.out.find(name), std::string::npos) << name;
}

TEST(FormatsCli, DescribesADsviewSessionAndItsDecoders) {
    const auto r =
        runDecode({"--formats", sourceDir() + "/tests/data/real/formats/dsview/demo_spi.dsl"});
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find("dsview-dsl, timebase 1/40000000 s, 6 signals"), std::string::npos)
        << r.out;
    EXPECT_NE(r.out.find("DSView decoders: [{\"channel\": [{\"miso\": 0}, {\"cs\": 2}"),
              std::string::npos)
        << r.out;
    EXPECT_NE(r.out.find("\"wordsize\": 8}"), std::string::npos) << r.out;
}

// A scope column is listed by the name --map takes, its title beside it; a VCD signal
// by its path, which --map takes too.
TEST(FormatsCli, ListsAScopeColumnByItsNameAndTitle) {
    const std::string keysight = sourceDir() + "/tests/data/real/formats/keysight/scope_3.csv";
    const auto r =
        runDecode({"--formats", keysight, sourceDir() + "/captures/spi_mode0_lsb16.vcd"});
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find("    0  CH1 (column '1')\n    1  CH2 (column '2')\n"), std::string::npos)
        << r.out;
    EXPECT_NE(r.out.find("    1  busdecode.sclk\n"), std::string::npos) << r.out;
    const auto unbound = runDecode({keysight, "--proto", "uart", "--map", "rx=3"});
    EXPECT_NE(unbound.err.find("(signals: CH1 (column '1'), CH2 (column '2'))"), std::string::npos)
        << unbound.err;
}

TEST(FormatsCli, BadFileIsOneLineExitTwo) {
    const std::string p = tempDir() + "/x.bin";
    writeFile(p, std::string("\x01\x02\x03\x00\x05", 5));
    const auto r = runDecode({"--formats", p});
    EXPECT_EQ(r.status, 2);
    EXPECT_EQ(r.err, "decode: " + p +
                         ": unknown format: binary data that is neither VCD, CSV nor a sigrok .sr "
                         "session\n");
}

// A capture with no time of its own is described without --rate, saying it needs one.
TEST(FormatsCli, DescribesAPlainCsvThatNeedsARate) {
    const std::string p = tempDir() + "/plain.csv";
    writeFile(p, "clk,data\n0,1\n1,0\n");
    auto r = runDecode({"--formats", p});
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.out, p + ": plain-csv, no time of its own (decode it with --rate HZ), 2 signals\n"
                         "    0  clk\n    1  data\n");
    r = runDecode({"--formats", p, "--rate", "1MHz"});
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find(": plain-csv, timebase 1/1000000 s, 2 signals"), std::string::npos)
        << r.out;
}

}  // namespace
}  // namespace busdecode::test
