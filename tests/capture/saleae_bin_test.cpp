// Saleae Logic 2 binary exports (digital, versions 0 and 1): a folder of channels or one
// file read back as the VCD of the same traffic; broken files named with what is wrong.
#include <gtest/gtest.h>

#include <filesystem>

#include "capture/capture_writer.h"
#include "capture_util.h"
#include "core/waveform.h"
#include "random_traffic.h"
#include "zip_builder.h"

namespace busdecode::test {
namespace {

Waveform traffic() {
    Waveform w = randomTraffic(Timebase::fromSampleRate(12'500'000), 11, 5000, 40, 100, 9);
    w.start = 7;
    return w;
}

TEST(SaleaeBin, FolderRoundTripVersions0And1) {
    const Waveform w = traffic();
    const std::string vcd = tempDir() + "/s.vcd";
    writeVcd(w, vcd);
    const Collected want = collectFile(vcd, {"clk", "data", "cs"});
    for (int version : {0, 1}) {
        SCOPED_TRACE(version);
        const std::string dir = tempDir() + "/export" + std::to_string(version);
        writeSaleaeBin(w, dir, version);
        const Collected c = collectFile(dir, {"0", "1", "digital_2"});
        EXPECT_EQ(c.format, "saleae-bin");
        EXPECT_EQ(c.initial, want.initial);
        // Ticks count from the capture's begin, so times are compared from there.
        std::vector<NsEdge> got = inNs(c), exp = inNs(want);
        ASSERT_EQ(got.size(), exp.size());
        const std::int64_t offset = w.timebase.toNs(w.start);
        for (std::size_t i = 0; i < got.size(); ++i) {
            EXPECT_EQ(got[i].line, exp[i].line);
            EXPECT_EQ(got[i].level, exp[i].level);
            EXPECT_NEAR(double(got[i].ns + offset), double(exp[i].ns), 1.0) << i;
        }
        if (version == 1) {
            EXPECT_EQ(c.tb.den / c.tb.num, 12'500'000);
        }
        // One channel's file alone.
        const Collected one = collectFile(dir + "/digital_1.bin");
        ASSERT_EQ(one.signals.size(), 1u);
        EXPECT_EQ(one.signals[0].name, "1");
    }
}

TEST(SaleaeBin, BrokenFiles) {
    const Waveform w = traffic();
    const std::string dir = tempDir() + "/broken";
    writeSaleaeBin(w, dir, 0);
    const std::string good = readFile(dir + "/digital_0.bin");
    std::string p = tempCapture("cut.bin", good.substr(0, good.size() - 12));
    EXPECT_NE(errorOf(p).find(p + ": chunk 0 header says"), std::string::npos) << errorOf(p);
    EXPECT_NE(errorOf(p).find("(truncated)"), std::string::npos);
    p = tempCapture("head.bin", good.substr(0, 20));
    EXPECT_EQ(errorOf(p), p + ": ends inside its chunk 0 header (truncated)");
    std::string v = good;
    v[8] = 2;
    p = tempCapture("v2.bin", v);
    EXPECT_EQ(errorOf(p),
              p + ": Saleae binary export version 2 is not read (versions 0 and 1 are)");
    v = good;
    v[12] = 1;
    p = tempCapture("analog.bin", v);
    // Read as an analog channel now: a digital file's bytes make no analog header.
    EXPECT_EQ(errorOf(p).rfind(p + ": ", 0), 0u) << errorOf(p);
    EXPECT_EQ(errorOf(p).find('\n'), std::string::npos);
    p = tempCapture("tail.bin", good + "xyz");
    EXPECT_EQ(errorOf(p), p + ": 3 bytes after the last transition (not a Saleae export?)");
    const std::string empty = tempDir() + "/nothing";
    std::filesystem::create_directories(empty);
    EXPECT_EQ(errorOf(empty),
              empty + ": is a directory without Saleae digital_N.bin or analog_N.bin files");
}

// The analog export's edges against the VCD's: the same lines and levels, each crossing of
// the threshold between the samples either side of the edge (12.5 MS/s).
void expectSameEdgesWithinASample(const Collected& got, const Collected& want) {
    const auto a = inNs(got), b = inNs(want);
    ASSERT_EQ(a.size(), b.size());
    const double period_ns = 1e9 / 12'500'000;
    for (std::size_t i = 0; i < a.size(); ++i) {
        ASSERT_EQ(a[i].line, b[i].line) << i;
        ASSERT_EQ(a[i].level, b[i].level) << i;
        ASSERT_NEAR(double(a[i].ns), double(b[i].ns), period_ns) << i;
    }
}

TEST(SaleaeBin, AnalogFolderReadsAsTheVcdThroughTheSchmittTrigger) {
    const Waveform w = traffic();
    const std::string vcd = tempDir() + "/a.vcd", dir = tempDir() + "/analog";
    writeVcd(w, vcd);
    writeSaleaeAnalogBin(w, dir, 3.3);
    const Collected want = collectFile(vcd, {"clk", "data", "cs"});
    const Collected got = collectFile(dir, {"analog_0", "analog_1", "analog_2"});
    EXPECT_EQ(got.format, "saleae-bin-analog");
    EXPECT_EQ(got.initial, want.initial);
    expectSameEdgesWithinASample(got, want);
    // One file alone; a cut file; a version this reader does not know.
    EXPECT_EQ(collectFile(dir + "/analog_1.bin").signals.size(), 1u);
    const std::string good = readFile(dir + "/analog_0.bin");
    std::string p = tempCapture("analog_cut.bin", good.substr(0, good.size() - 6));
    EXPECT_NE(errorOf(p).find(p + ": says "), std::string::npos) << errorOf(p);
    EXPECT_NE(errorOf(p).find("(truncated)"), std::string::npos);
    std::string v2 = good;
    v2[8] = 2;
    p = tempCapture("analog_v2.bin", v2);
    EXPECT_EQ(errorOf(p),
              p + ": Saleae analog export version 2 is not read (versions 0 and 1 are)");
}

TEST(SaleaeBin, AnalogVersion1InTwoWaveformsReadsAsTheVcd) {
    const Waveform w = traffic();
    const std::string vcd = tempDir() + "/a1.vcd", dir = tempDir() + "/analog_v1";
    writeVcd(w, vcd);
    writeSaleaeAnalogBin(w, dir, 3.3, 1);
    const Collected want = collectFile(vcd, {"clk", "data", "cs"});
    const Collected got = collectFile(dir, {"analog_0", "analog_1", "analog_2"});
    EXPECT_EQ(got.format, "saleae-bin-analog");
    EXPECT_EQ(got.initial, want.initial);
    expectSameEdgesWithinASample(got, want);
}

TEST(SaleaeBin, BrokenAnalogVersion1NamesTheWaveform) {
    const Waveform w = traffic();
    const std::string dir = tempDir() + "/analog_v1_broken";
    writeSaleaeAnalogBin(w, dir, 3.3, 1);
    const std::string good = readFile(dir + "/analog_0.bin");
    // Common header 16, waveform count 8, then waveform 0's 40-byte header at byte 24.
    std::string p = tempCapture("v1_cut.bin", good.substr(0, good.size() - 6));
    EXPECT_NE(errorOf(p).find(p + ": waveform 1 at byte "), std::string::npos) << errorOf(p);
    EXPECT_NE(errorOf(p).find("(truncated)"), std::string::npos) << errorOf(p);
    std::string bad = good;
    bad[24 + 16 + 7] = char(0xff);  // waveform 0's sample rate: a NaN
    p = tempCapture("v1_rate.bin", bad);
    EXPECT_NE(errorOf(p).find(p + ": waveform 0 at byte 24: begin "), std::string::npos)
        << errorOf(p);
    p = tempCapture("v1_tail.bin", good + "ab");
    EXPECT_EQ(errorOf(p), p + ": 2 bytes after the last waveform");
    bad = good;
    bad[16] = 9;  // nine waveforms where two are
    p = tempCapture("v1_count.bin", bad);
    EXPECT_NE(errorOf(p).find(p + ": waveform 2 of 9 at byte "), std::string::npos) << errorOf(p);
}

TEST(SaleaeBin, SalSessionRefusedPointingToTheExport) {
    const std::string p =
        tempCapture("x.sal", fuzz::buildStoredZip({{"meta.json", "{\"version\": 22}"}}));
    EXPECT_NE(errorOf(p).find(p + ": a Saleae Logic 2 session (.sal): its format is "
                                  "undocumented"),
              std::string::npos)
        << errorOf(p);
    EXPECT_NE(errorOf(p).find("Export Data > Binary"), std::string::npos);
}

}  // namespace
}  // namespace busdecode::test
