// The text and HTML reports rendered from hand-made events, the bit layout of the
// timing diagram, and the atomic file writer behind the report sink.
#include <gtest/gtest.h>

#include <filesystem>
#include <regex>
#include <sstream>

#include "core/atomic_file.h"
#include "report/capture_stats.h"
#include "report/frame_layout.h"
#include "report/html_report.h"
#include "report/report_format.h"
#include "report/report_sink.h"
#include "report/text_report.h"
#include "support/paths.h"
#include "test_events.h"

namespace busdecode {
namespace {

using test::bisscFrame;

CaptureStats faultyBiss(const std::string& file = "enc.vcd") {
    CaptureStats s;
    auto f = test::facts(100'000'000, file);
    s.begin(f);
    for (int i = 0; i < 500; ++i)
        s.add(bisscFrame(Tick(i) * 100000, 1000 + 3 * i, i != 123, 1, i == 200 ? 0 : 1, 1e6,
                         80 + i % 40));
    s.add(test::bisscRegister(60'000'000, 0x7E, 0x69));
    s.end(f);
    return s;
}

std::size_t countOf(const std::string& text, const std::string& what) {
    std::size_t n = 0;
    for (auto p = text.find(what); p != std::string::npos; p = text.find(what, p + 1))
        ++n;
    return n;
}

// proc_cycles 0 (39 frames) and 5 (one): a row per value, not "0 .. 0.625".
TEST(ReportFormat, WholeNumbersGetARowPerValue) {
    QuantileSketch s;
    for (int i = 0; i < 39; ++i)
        s.add(0);
    s.add(5);
    const auto rows = textHistogram("proc_cycles", s, 8, 10);
    ASSERT_EQ(rows.size(), 6u);
    EXPECT_EQ(rows[0], "           0                 |##########| 39");
    EXPECT_EQ(rows[5], "           5                 |#         | 1");
    for (const auto& r : rows)
        EXPECT_EQ(r.find(".."), std::string::npos) << r;
}

TEST(ReportFormat, FrequencyInHzKhzMhzGhz) {
    EXPECT_EQ(formatFrequency(12), "12 Hz");
    EXPECT_EQ(formatFrequency(250e3), "250.000 kHz");
    EXPECT_EQ(formatFrequency(999999.9999), "1.000 MHz");  // the unit after rounding
    EXPECT_EQ(formatFrequency(12.5e6), "12.500 MHz");
    EXPECT_EQ(formatFrequency(2.4e9), "2.400 GHz");
    EXPECT_EQ(formatFrequency(5e12), "5000.000 GHz");  // GHz at most
    EXPECT_EQ(formatFrequency(-250e3), "-250.000 kHz");
}

TEST(TextReport, HasFactsCountsTimingPositionAndFaults) {
    const std::string r = renderTextReport(faultyBiss());
    EXPECT_NE(r.find("file        enc.vcd"), std::string::npos) << r;
    EXPECT_NE(r.find("bissc.ma = MA"), std::string::npos);
    EXPECT_NE(r.find("Bus bissc"), std::string::npos);
    EXPECT_NE(r.find("frame             500 events, 1 with faults (crc 1)"), std::string::npos)
        << r;
    EXPECT_NE(r.find("nW                 active 1 of 500"), std::string::npos) << r;
    EXPECT_NE(r.find("0x7E"), std::string::npos);
    EXPECT_NE(r.find("position    min 1000  max 2497"), std::string::npos) << r;
    EXPECT_NE(r.find("line_delay_ns"), std::string::npos);
    EXPECT_NE(r.find("pause between"), std::string::npos);
    EXPECT_NE(r.find("|#"), std::string::npos);  // a text histogram
    EXPECT_NE(r.find("Faults: 1 event with errors"), std::string::npos) << r;
    EXPECT_NE(r.find("0.012300000 s"), std::string::npos) << r;  // the faulty frame's time
}

// A position that never changed has no largest jump to place in time.
TEST(TextReport, APositionThatNeverChangedSaysSo) {
    CaptureStats s;
    auto f = test::facts(100'000'000, "still.vcd");
    s.begin(f);
    for (int i = 0; i < 5; ++i)
        s.add(bisscFrame(Tick(i) * 100000, 4242, true, 1, 1, 1e6, 100));
    s.end(f);
    const std::string text = renderTextReport(s);
    EXPECT_NE(text.find("it never changed"), std::string::npos) << text;
    EXPECT_EQ(text.find("largest jump"), std::string::npos) << text;
    EXPECT_NE(renderHtmlReport(s).find("; it never changed."), std::string::npos);
}

TEST(TextReport, TimingHeadingsSitOverTheirColumns) {
    const std::string r = renderTextReport(faultyBiss());
    std::istringstream in(r);
    std::string line, heading, row;
    while (std::getline(in, line)) {
        if (line.rfind("  frame timing", 0) == 0) heading = line;
        if (line.rfind("    line_delay_ns", 0) == 0) row = line;
    }
    ASSERT_FALSE(heading.empty()) << r;
    ASSERT_FALSE(row.empty()) << r;
    // Right-aligned columns: each heading ends where the numbers under it end.
    EXPECT_EQ(heading.size(), row.size()) << heading << "\n" << row;
    const auto n_end = heading.find(" n ") + 2;
    EXPECT_EQ(row.substr(n_end - 3, 3), "500") << heading << "\n" << row;
}

TEST(TextReport, CleanCaptureSaysNoFaults) {
    CaptureStats s;
    s.begin(test::facts(1'000'000));
    s.add(bisscFrame(0, 5));
    s.add(bisscFrame(100000, 6));
    EXPECT_NE(renderTextReport(s).find("Faults: none"), std::string::npos);
}

TEST(HtmlReport, SelfContainedWithPositionHistogramAndTimingDiagram) {
    const std::string h = renderHtmlReport(faultyBiss("a<b>&c.vcd"));
    EXPECT_EQ(h.rfind("<!DOCTYPE html>", 0), 0u);
    EXPECT_NE(h.find("</html>"), std::string::npos);
    EXPECT_EQ(h.find("<script"), std::string::npos);
    EXPECT_EQ(h.find("src="), std::string::npos);  // nothing fetched
    EXPECT_EQ(h.find("href="), std::string::npos);
    EXPECT_NE(h.find("a&lt;b&gt;&amp;c.vcd"), std::string::npos);
    EXPECT_EQ(h.find("a<b>"), std::string::npos);
    EXPECT_EQ(countOf(h, "<svg class=\"position\""), 1u);
    EXPECT_GE(countOf(h, "<svg class=\"histogram\""), 1u);
    EXPECT_NE(h.find("frame line_delay_ns"), std::string::npos);
    EXPECT_EQ(countOf(h, "<svg class=\"timing\""), 1u);
    EXPECT_EQ(countOf(h, "<svg"), countOf(h, "</svg>"));
    // The timing diagram draws MA and SL with the CRC segment marked faulty.
    const auto t = h.find("<svg class=\"timing\"");
    const std::string timing = h.substr(t, h.find("</svg>", t) - t);
    EXPECT_NE(timing.find(">MA<"), std::string::npos);
    EXPECT_NE(timing.find(">SL<"), std::string::npos);
    EXPECT_NE(timing.find(">CRC<"), std::string::npos);
    EXPECT_NE(timing.find("errors: crc"), std::string::npos);
    EXPECT_NE(timing.find("#ffcdd2"), std::string::npos);  // faulty segment / field colour
}

// Whole numbers of ns over a short span, drawn in us (2.000 to 2.039): a bar per value,
// and ticks on the axis's unit, not at raw ns far off it.
TEST(HtmlReport, APerValueHistogramInMicrosecondsHasTicks) {
    CaptureStats s;
    auto f = test::facts(100'000'000, "us.vcd");
    s.begin(f);
    for (int i = 0; i < 200; ++i)
        s.add(bisscFrame(Tick(i) * 100000, 1000 + i, true, 1, 1, 1e6, 2000 + i % 40));
    s.end(f);
    const std::string h = renderHtmlReport(s);
    const auto at = h.find("frame line_delay_ns (n=200)");
    ASSERT_NE(at, std::string::npos);
    const auto from = h.rfind("<svg class=\"histogram\"", at);
    const std::string svg = h.substr(from, h.find("</svg>", at) - from);
    EXPECT_GE(countOf(svg, "class=\"tick x\""), 4u) << svg;
    EXPECT_NE(svg.find(">2.010<"), std::string::npos) << svg;
}

TEST(FrameLayout, BisscWidthFollowsFromTheClockCount) {
    const Event e = bisscFrame(0, 0x2AAAAAA, false);
    const auto segs = frameLayout(e);
    ASSERT_EQ(segs.size(), 8u);  // ACK S CDS POS nE nW CRC STP
    EXPECT_EQ(segs[0].label, "ACK");
    EXPECT_EQ(segs[3].label, "POS");
    EXPECT_EQ(segs[3].bits.size(), 26u);
    EXPECT_EQ(segs[3].bits[0], 1);
    EXPECT_EQ(segs[3].bits[1], 0);
    EXPECT_EQ(segs[6].label, "CRC");
    EXPECT_TRUE(segs[6].fault);
    EXPECT_EQ(segs[6].bits, (std::vector<int>{0, 1, 0, 1, 0, 1}));  // crc_rx 0x15
}

TEST(FrameLayout, SsiRawWordMsbFirstAndNoneForUnknownEvents) {
    const auto segs = frameLayout(test::ssiFrame(0, 0x1000001));
    ASSERT_EQ(segs.size(), 1u);
    ASSERT_EQ(segs[0].bits.size(), 25u);
    EXPECT_EQ(segs[0].bits.front(), 1);
    EXPECT_EQ(segs[0].bits.back(), 1);
    Event other;
    other.proto = "uart";
    other.type = "byte";
    other.set("value", std::int64_t(0x41));
    EXPECT_TRUE(frameLayout(other).empty());
}

TEST(AtomicFile, ReplacesTheTargetAndLeavesNoTemporary) {
    const std::string dir = test::tempDir() + "/atomic";
    std::filesystem::create_directories(dir);
    const std::string path = dir + "/out.txt";
    writeFileAtomically(path, "first");
    writeFileAtomically(path, "second");
    EXPECT_EQ(test::readFile(path), "second");
    std::size_t files = 0;
    for (const auto& entry : std::filesystem::directory_iterator(dir)) {
        (void)entry;
        ++files;
    }
    EXPECT_EQ(files, 1u);
    EXPECT_THROW(writeFileAtomically(dir + "/missing/dir/x.txt", "x"), InputError);
}

TEST(ReportSink, WritesTextOrHtmlByExtensionAtTheEnd) {
    const std::string dir = test::tempDir();
    for (const std::string name : {"r.txt", "r.HTML"}) {
        const std::string path = dir + "/" + name;
        auto sink = makeReportSink(path);
        const auto f = test::facts(1'000'000);
        sink->begin(f);
        sink->onEvent(bisscFrame(0, 1, false), f);
        EXPECT_FALSE(std::filesystem::exists(path));  // nothing half-written during the pass
        sink->end(f);
        const std::string text = test::readFile(path);
        if (name == "r.txt")
            EXPECT_EQ(text.rfind("busdecode report", 0), 0u);
        else
            EXPECT_EQ(text.rfind("<!DOCTYPE html>", 0), 0u);
    }
}

}  // namespace
}  // namespace busdecode
