// Which capture a JSON line came from, and when the capture began: `capture` on every line
// when several captures are decoded in one call, `capture_start` from a VCD's $date, and
// times that restart with each capture (docs/contract.md, "JSON lines").
#include <gtest/gtest.h>

#include <sstream>

#include "capture/capture_reader.h"
#include "capture/wall_clock.h"
#include "fault_captures.h"
#include "support/paths.h"

namespace busdecode {
namespace {

std::vector<std::string> lines(const std::string& s) {
    std::vector<std::string> out;
    std::istringstream in(s);
    for (std::string l; std::getline(in, l);)
        out.push_back(l);
    return out;
}

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

TEST(CaptureField, OneCaptureKeepsItsLinesAsTheyWere) {
    const auto r = test::runDecode({ssiCapture(), "--proto", "ssi", "--format", "jsonl"});
    ASSERT_EQ(r.status, 0) << r.err;
    const auto out = lines(r.out);
    ASSERT_FALSE(out.empty());
    EXPECT_EQ(out[0].rfind("{\"proto\":\"ssi\",\"type\":\"frame\",\"start_ns\":", 0), 0u) << out[0];
    EXPECT_EQ(r.out.find("\"capture"), std::string::npos);
}

TEST(CaptureField, SeveralCapturesNameTheirsAndTheirStart) {
    const std::string plain = ssiCapture(), dated = datedCopy(plain);
    const auto r = test::runDecode({plain, dated, "--proto", "ssi", "--format", "jsonl"});
    ASSERT_EQ(r.status, 0) << r.err;
    const auto out = lines(r.out);
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
