// Which capture a JSON line came from, and when the capture began: `capture` on every line
// when several captures are decoded in one call, `capture_start` from a VCD's $date, and
// times that restart with each capture (docs/contract.md, "JSON lines").
#include <gtest/gtest.h>

#include <sstream>

#include "capture/capture_reader.h"
#include "capture/scope_csv_writer.h"
#include "capture/wall_clock.h"
#include "core/waveform.h"
#include "fault_captures.h"
#include "support/paths.h"
#include "zip_builder.h"

namespace busdecode {
namespace {

// The SSI capture with a recording date in its header.
std::string datedCopy(const std::string& capture) {
    const std::string path = test::tempDir() + "/dated.vcd";
    test::writeFile(path, "$date\n\tSun Nov 22 23:28:18 2026\n$end\n" + test::readFile(capture));
    return path;
}

std::string ssiCapture() {
    for (const auto& c : test::faultCaptures(test::tempDir() + "/verify"))
        if (c.proto == "ssi" && c.failing_rule.empty()) return c.path;
    return "";
}

TEST(WallClock, KnownLayoutsBecomeIso8601) {
    EXPECT_EQ(wallClockFromText("  Sun Nov 22 23:28:18 2026 "), "2026-11-22T23:28:18");
    EXPECT_EQ(wallClockFromText("2024-02-12T10:00:00"), "2024-02-12T10:00:00");
    EXPECT_EQ(wallClockFromText("2024-02-12 10:00:00"), "2024-02-12T10:00:00");
    EXPECT_EQ(wallClockFromText("Feb 12, 2024 10:00:00"), "2024-02-12T10:00:00");
    EXPECT_EQ(wallClockFromText("last Tuesday"), "last Tuesday");  // passed on as written
    EXPECT_EQ(wallClockFromText(" \n"), "");
}

TEST(WallClock, AVcdDateIsTheCapturesStart) {
    // sigrok-cli wrote this one ("$date Sun Nov 22 23:28:18 2026 $end").
    auto reader = openCapture(test::sourceDir() + "/captures/uart_rxtx_overlapped_sigrok-cli.vcd",
                              OpenOptions{});
    EXPECT_EQ(reader->wallClockStart(), "2026-11-22T23:28:18");
    auto undated = openCapture(ssiCapture(), OpenOptions{});
    EXPECT_EQ(undated->wallClockStart(), "");
}

TEST(WallClock, InstantsAndOtherToolsLayouts) {
    EXPECT_EQ(wallClockFromUnixMs(1622598460321), "2021-06-02T01:47:40.321Z");
    EXPECT_EQ(wallClockFromUnixMs(0), "1970-01-01T00:00:00.000Z");
    EXPECT_EQ(wallClockFromText("22-Jan-2015 11:35:11"), "2015-01-22T11:35:11");
    EXPECT_EQ(wallClockOfSigrokComment("from Session-emulating driver on Sun Nov 22 06:44:45 2026"),
              "2026-11-22T06:44:45");
    EXPECT_EQ(wallClockOfSigrokComment("Channels (2/8): MA, SLO"), "");
    EXPECT_EQ(wallClockOfLecroySegment("#1,22-Jan-2015 11:35:11,0   "), "2015-01-22T11:35:11");
    EXPECT_EQ(wallClockOfLecroySegment("#2,22-Jan-2015 11:35:12,0.5"), "");
}

std::string startOfFile(const std::string& path) {
    return openCapture(path, OpenOptions{})->wallClockStart();
}

// Each format that carries a time gives it; the others give "" (docs/contract.md).
TEST(WallClock, RealFilesOfOtherTools) {
    const std::string real = test::sourceDir() + "/tests/data/real/";
    // DSView: "trigger time = 1622598460321" (ms since 1970), "trigger pos = 0".
    EXPECT_EQ(startOfFile(real + "formats/dsview/demo_spi.dsl"), "2021-06-02T01:47:40.321Z");
    // sigrok CSV: "; from Session-emulating driver on Sun Nov 22 06:44:45 2026".
    EXPECT_EQ(startOfFile(real + "biss-renishaw/sigrok-csv/renishaw_biss_1MHz.csv"),
              "2026-11-22T06:44:45");
    // DSView's demo session never triggered ("trigger time = -28800000"), a sigrok session
    // (its metadata has no date), scope CSVs of Keysight, Rigol, Tektronix, PicoScope: none.
    for (const char* file :
         {"formats/dsview/protocol.demo", "formats/tek-mdo/RTC.sr", "formats/tek-mdo/RTC.csv",
          "formats/keysight/scope_3.csv", "formats/rigol/DS1052E.csv",
          "formats/mixed-gpl/rigol_ds1000z_mixed_signal.csv",
          "formats/mixed-gpl/picoscope6_excerpt.csv"}) {
        SCOPED_TRACE(file);
        EXPECT_EQ(startOfFile(real + file), "");
    }
}

// A DSView session's header with `lines` after the rate; one probe, 100 samples.
std::string dslWith(const std::string& name, const std::string& lines) {
    const std::string header =
        "[version]\nversion = 2\n[header]\ndevice mode = 0\ntotal samples = 100\n"
        "total probes = 1\ntotal blocks = 1\nsamplerate = 1 MHz\n" +
        lines + "probe0 = a\n";
    const std::string path = test::tempDir() + "/" + name;
    test::writeFile(path,
                    fuzz::buildStoredZip({{"header", header}, {"L-0/0", std::string(16, 'U')}}));
    return path;
}

TEST(WallClock, DsviewTriggerLessItsPosition) {
    // Triggered 2 s (2000000 samples at 1 MHz) into the capture.
    EXPECT_EQ(
        startOfFile(dslWith("pos.dsl", "trigger time = 1622598460321\ntrigger pos = 2000000\n")),
        "2021-06-02T01:47:38.321Z");
    // Metadata never refuses a file: a time that is no number, or absurd, is no time.
    EXPECT_EQ(startOfFile(dslWith("text.dsl", "trigger time = soon\n")), "");
    EXPECT_EQ(startOfFile(dslWith(
                  "far.dsl", "trigger time = 1622598460321\ntrigger pos = 9223372036854775807\n")),
              "");
}

TEST(WallClock, LecroyCsvGivesItsFirstSegmentsTriggerTime) {
    WaveBuilder b(Timebase{1, 1'000'000'000}, {"CH1"}, {1});
    for (int i = 1; i < 40; ++i)
        b.setNs(0, 1000.0 * i, i % 2 == 0);
    const std::string path = test::tempDir() + "/lecroy_dated.csv";
    AnalogStyle style;
    writeScopeCsv(b.build(b.ticksFromNs(41000)), path, ScopeDialect::LeCroy, style);
    ASSERT_NE(test::readFile(path).find("#1,22-Jan-2015 11:35:11,"), std::string::npos);
    EXPECT_EQ(startOfFile(path), "2015-01-22T11:35:11");
}

TEST(CaptureField, OneCaptureKeepsItsLinesAsTheyWere) {
    const auto r = test::runDecode({ssiCapture(), "--proto", "ssi", "--format", "jsonl"});
    ASSERT_EQ(r.status, 0) << r.err;
    const auto out = test::splitLines(r.out);
    ASSERT_FALSE(out.empty());
    EXPECT_EQ(out[0].rfind("{\"proto\":\"ssi\",\"type\":\"frame\",\"start_ns\":", 0), 0u) << out[0];
    EXPECT_EQ(r.out.find("\"capture"), std::string::npos);
}

TEST(CaptureField, SeveralCapturesNameTheirsAndTheirStart) {
    const std::string plain = ssiCapture(), dated = datedCopy(plain);
    const auto r = test::runDecode({plain, dated, "--proto", "ssi", "--format", "jsonl"});
    ASSERT_EQ(r.status, 0) << r.err;
    const auto out = test::splitLines(r.out);
    ASSERT_EQ(out.size() % 2, 0u);
    const std::size_t half = out.size() / 2;
    const std::string first =
        "{\"proto\":\"ssi\",\"type\":\"frame\",\"capture\":\"" + plain + "\",\"start_ns\":";
    const std::string second = "{\"proto\":\"ssi\",\"type\":\"frame\",\"capture\":\"" + dated +
                               "\",\"capture_start\":\"2026-11-22T23:28:18\",\"start_ns\":";
    EXPECT_EQ(out[0].rfind(first, 0), 0u) << out[0];
    EXPECT_EQ(out[half].rfind(second, 0), 0u) << out[half];
    // Times restart with each capture: the same traffic, the same start_ns.
    auto startOf = [](const std::string& l) {
        const auto at = l.find("\"start_ns\":") + 11;
        return l.substr(at, l.find(',', at) - at);
    };
    EXPECT_EQ(startOf(out[0]), startOf(out[half]));
    for (std::size_t i = 0; i < out.size(); ++i)
        EXPECT_NE(out[i].find(i < half ? plain : dated), std::string::npos) << out[i];
}

}  // namespace
}  // namespace busdecode
