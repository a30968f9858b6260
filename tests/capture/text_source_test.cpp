// TextSource::skipLinesEqualTo, which the dense CSV reader uses to count a row's repeats
// without returning them one by one: both compare paths (lines up to 8 bytes with their
// newline, longer ones), both line ends, the stops, and runs longer than the read buffer.
#include <gtest/gtest.h>

#include <string>

#include "capture/text_source.h"
#include "capture_util.h"

namespace busdecode::test {
namespace {

// Reads `text` line by line, skipping the repeats of each line; returns "line:repeats"
// for each line returned, and checks that lineNo() counts the repeats.
std::string walk(const std::string& name, const std::string& text) {
    TextSource src(tempCapture(name, text), {});
    std::string out;
    std::uint64_t expect_no = 0;
    std::string_view line;
    while (src.nextLine(line) == TextSource::Status::Line) {
        EXPECT_EQ(src.lineNo(), ++expect_no);
        const std::string copy(line);
        const std::uint64_t n = src.skipLinesEqualTo(line);
        expect_no += n;
        EXPECT_EQ(src.lineNo(), expect_no);
        out += copy + ":" + std::to_string(n) + " ";
    }
    return out;
}

TEST(TextSourceSkip, ShortLinesOneLoadEach) {
    EXPECT_EQ(walk("short.csv", "1,0\n1,0\n1,0\n0,0\n0,0\n1,0\n"), "1,0:2 0,0:1 1,0:0 ");
    // Exactly 8 bytes with the newline, and a line that only starts like the repeated one.
    EXPECT_EQ(walk("eight.csv", "1,0,1,0\n1,0,1,0\n1,0,1,0\n1,0,1,01\n1,0,1,0\n"),
              "1,0,1,0:2 1,0,1,01:0 1,0,1,0:0 ");
}

TEST(TextSourceSkip, LongLinesAndWindowsLineEnds) {
    EXPECT_EQ(walk("long.csv", "1,0,1,0,1\n1,0,1,0,1\n1,0,1,0,1\n1,0,1,0,0\n"),
              "1,0,1,0,1:2 1,0,1,0,0:0 ");
    EXPECT_EQ(walk("crlf.csv", "1,0\r\n1,0\r\n1,0\r\n0,0\r\n"), "1,0:2 0,0:0 ");
    // A line that differs only in its line end is not a repeat.
    EXPECT_EQ(walk("mixed_eol.csv", "1,0\r\n1,0\n1,0\r\n"), "1,0:0 1,0:0 1,0:0 ");
}

TEST(TextSourceSkip, StopsAtTheEndOfTheInput) {
    // The last line has no newline: it is returned, never skipped (nor are the lines
    // whose 8-byte load would reach past the input: nextLine() returns those).
    EXPECT_EQ(walk("tail.csv", "1,0\n1,0\n1,0\n1,0\n1,0"), "1,0:2 1,0:0 1,0:0 ");
    // Nothing to skip after a line not just returned by nextLine().
    TextSource src(tempCapture("other.csv", "1,0\n1,0\n"), {});
    std::string_view line;
    ASSERT_EQ(src.nextLine(line), TextSource::Status::Line);
    const std::string copy(line);
    EXPECT_EQ(src.skipLinesEqualTo(copy), 0u);
    EXPECT_EQ(src.lineNo(), 1u);
}

TEST(TextSourceSkip, RunsLongerThanTheReadBuffer) {
    // 300 000 repeats of a 4-byte line (1.2 MB) and of a 12-byte one: the buffer is
    // refilled many times; every repeat is counted once, wherever a refill cuts the run.
    for (const std::string row : {"1,0", "1,0,1,0,1,0"}) {
        std::string text;
        for (int i = 0; i < 300000; ++i)
            text += row + "\n";
        text += "0\n";
        TextSource src(tempCapture("run.csv", text), {});
        std::uint64_t lines = 0, repeats = 0;
        std::string_view line;
        while (src.nextLine(line) == TextSource::Status::Line) {
            ++lines;
            if (line == row) repeats += src.skipLinesEqualTo(line) + 1;
        }
        EXPECT_EQ(repeats, 300000u) << row;
        EXPECT_EQ(src.lineNo(), 300001u) << row;
        EXPECT_LT(lines, 1000u) << row;  // nearly all of them skipped, not returned
    }
}

}  // namespace
}  // namespace busdecode::test
