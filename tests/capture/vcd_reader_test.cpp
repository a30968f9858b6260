// The VCD reader: dialect features on small inline files, and every error message.
#include <gtest/gtest.h>

#include "capture/vector_range.h"
#include "capture_util.h"

namespace busdecode::test {
namespace {

std::vector<Edge> E(std::initializer_list<Edge> l) {
    return l;
}

TEST(VcdReader, SigrokDialectSeveralChangesPerLine) {
    auto p = tempCapture(
        "sigrok.vcd",
        "$date x $end\n$version libsigrok $end\n$comment\n  Acquisition with 2/8 channels\n$end\n"
        "$timescale 100 ps $end\n$scope module libsigrok $end\n$var wire 1 ! MA $end\n"
        "$var wire 1 \" SLO $end\n$upscope $end\n$enddefinitions $end\n"
        "#0 1! 0\"\n#10 0! 1\"\n#25 1!\n#40\n");
    auto c = collectFile(p);
    EXPECT_EQ(c.format, "vcd");
    ASSERT_EQ(c.signals.size(), 2u);
    EXPECT_EQ(c.signals[0].full_name, "libsigrok.MA");
    EXPECT_EQ(c.signals[0].name, "MA");
    EXPECT_EQ(c.tb.num, 100);
    EXPECT_EQ(c.tb.den, 1'000'000'000'000);
    EXPECT_EQ(c.initial, (std::vector<std::uint8_t>{1, 0}));
    EXPECT_EQ(c.start, 0);
    EXPECT_EQ(c.end, 40);
    EXPECT_EQ(c.edges, E({{10, 0, 0}, {10, 1, 1}, {25, 0, 1}}));
}

// An Edge holds times up to 2^55 - 1 ticks (core/edge.h): a time of 15 digits and the
// last one it holds (17 digits) are read exactly, and one more is refused.
TEST(VcdReader, TimesUpToWhatAnEdgeHolds) {
    const std::string head =
        "$timescale 1 ps $end\n$var wire 1 ! a $end\n$enddefinitions $end\n#0 0!\n";
    auto c =
        collectFile(tempCapture("late.vcd", head + "#999999999999999 1!\n#36028797018963967 0!\n"));
    EXPECT_EQ(c.edges, E({{999999999999999, 0, 1}, {kMaxEdgeTick, 0, 0}}));
    EXPECT_EQ(c.end, kMaxEdgeTick);
    const std::string p = tempCapture("later.vcd", head + "#36028797018963968 1!\n");
    EXPECT_EQ(errorOf(p), p + ":5: time beyond 2^55 - 1 ticks (36028797018963967)");
}

TEST(VcdReader, TimescaleForms) {
    struct Case {
        const char* text;
        std::int64_t num, den;
    } cases[] = {{"1ns", 1, 1'000'000'000},          {"1 ns", 1, 1'000'000'000},
                 {"100 ps", 100, 1'000'000'000'000}, {"10us", 10, 1'000'000},
                 {"1 fs", 1, 1'000'000'000'000'000}, {"1 s", 1, 1},
                 {"\n  10\n  ms\n", 10, 1000}};
    for (const auto& cs : cases) {
        auto p =
            tempCapture("ts.vcd", std::string("$timescale ") + cs.text +
                                      " $end\n$var wire 1 a x $end\n$enddefinitions $end\n#0 1a\n");
        auto c = collectFile(p);
        EXPECT_EQ(c.tb.num, cs.num) << cs.text;
        EXPECT_EQ(c.tb.den, cs.den) << cs.text;
    }
    auto p = tempCapture("ts2.vcd",
                         "$timescale\n 1ns\n$end\n$var wire 1 a x $end\n$enddefinitions $end\n");
    EXPECT_EQ(collectFile(p).tb.den, 1'000'000'000);
}

TEST(VcdReader, NestedScopesAndLongIdentifiers) {
    auto p = tempCapture(
        "nest.vcd",
        "$timescale 1ns $end\n$scope module top $end\n$scope module enc $end\n"
        "$var wire 1 abc!~ clk $end\n$upscope $end\n$var wire 1 ## data $end\n"
        "$upscope $end\n$var wire 1 zz9_long_identifier cs $end\n$enddefinitions $end\n"
        "#5\n0abc!~\n1##\n0zz9_long_identifier\n#7\n1abc!~\n0##\n1zz9_long_identifier\n");
    auto c = collectFile(p);
    ASSERT_EQ(c.signals.size(), 3u);
    EXPECT_EQ(c.signals[0].full_name, "top.enc.clk");
    EXPECT_EQ(c.signals[0].name, "clk");
    EXPECT_EQ(c.signals[1].full_name, "top.data");
    EXPECT_EQ(c.signals[2].full_name, "cs");
    EXPECT_EQ(c.start, 5);
    EXPECT_EQ(c.initial, (std::vector<std::uint8_t>{0, 1, 0}));
    EXPECT_EQ(c.edges, E({{7, 0, 1}, {7, 1, 0}, {7, 2, 1}}));
}

TEST(VcdReader, OnlySelectedSignalsAndEdgeLineIsSelectionIndex) {
    auto p = tempCapture(
        "sel.vcd",
        "$timescale 1ns $end\n$var wire 1 ! a $end\n$var wire 1 \" b $end\n"
        "$var wire 1 # c $end\n$enddefinitions $end\n#0 0! 0\" 0#\n#1 1!\n#2 1\"\n#3 1#\n");
    auto c = collectFile(p, {"c", "a"});
    EXPECT_EQ(c.edges, E({{1, 1, 1}, {3, 0, 1}}));
}

TEST(VcdReader, DumpKeywordsCommentsAndEndOnLaterLine) {
    auto p = tempCapture("dump.vcd",
                         "$timescale 1ns $end\n$var wire 1 ! a $end\n$enddefinitions\n$end\n"
                         "$comment a comment with 1! inside $end\n"
                         "$dumpvars\n0!\n$end\n#0\n#10\n$comment\n 0! #5 also ignored\n$end\n1!\n"
                         "$dumpoff\nx!\n$end\n#20\n$dumpon\n0!\n$end\n#30 $dumpall 0! $end\n");
    auto c = collectFile(p);
    EXPECT_EQ(c.initial, (std::vector<std::uint8_t>{0}));
    // x in $dumpoff keeps the level; $dumpon's 0 at #20 is the change.
    EXPECT_EQ(c.edges, E({{10, 0, 1}, {20, 0, 0}}));
    EXPECT_EQ(c.end, 30);
}

TEST(VcdReader, XandZKeepThePreviousLevelAndReadOneBeforeAnyLevel) {
    auto p =
        tempCapture("xz.vcd",
                    "$timescale 1ns $end\n$var wire 1 ! a $end\n$var wire 1 \" b $end\n"
                    "$enddefinitions $end\n#0 x! 0\"\n#1 0! z\"\n#2 X!\n#3 1! 1\"\n#4 Z! 0\"\n");
    auto c = collectFile(p);
    EXPECT_EQ(c.initial, (std::vector<std::uint8_t>{1, 0}));  // x before any level reads 1
    EXPECT_EQ(c.edges, E({{1, 0, 0}, {3, 0, 1}, {3, 1, 1}, {4, 1, 0}}));
}

TEST(VcdReader, VectorBitsAndReals) {
    auto p = tempCapture(
        "vec.vcd",
        "$timescale 1 ns $end\n$scope module t $end\n$var wire 8 # bus [7:0] $end\n"
        "$var real 64 % volts $end\n$var wire 1 & bit[3] $end\n$upscope $end\n"
        "$enddefinitions $end\n#0\nb1010 #\nr0 %\n0&\n#1\nb1 #\nr3.3 %\n#2\nbx1 #\nr0.0 %\n"
        "#3\nb11110000 #\n1&\n#4 bz #\n");
    auto all = collectFile(p);
    ASSERT_EQ(all.signals.size(), 3u);
    EXPECT_EQ(all.signals[0].name, "bus");
    EXPECT_EQ(all.signals[0].width, 8);
    EXPECT_EQ(all.signals[2].name, "bit[3]");
    auto c = collectFile(p, {"bus[0]", "bus[1]", "bus[3]", "volts", "bus[7]"});
    // b1010: bit0=0 bit1=1 bit3=1, bit7 extends with 0
    EXPECT_EQ(c.initial, (std::vector<std::uint8_t>{0, 1, 1, 0, 0}));
    EXPECT_EQ(c.edges, E({{1, 0, 1},
                          {1, 1, 0},
                          {1, 2, 0},
                          {1, 3, 1},
                          // bx1: bit0=1, bit1 = x (kept), bit3 = x extension (kept)
                          {2, 3, 0},
                          // b11110000
                          {3, 0, 0},
                          {3, 4, 1}}));
}

TEST(VcdReader, BitSelectsFollowTheDeclaredRange) {
    // VHDL's `(0 to 1)` dumps as [0:1]: bus[0] is the MSB, the first digit of b10.
    // An offset [4:3] names its LSB bus[3]. Both forms, with and without a space.
    auto p = tempCapture("ranges.vcd",
                         "$timescale 1 ns $end\n$var wire 2 ! up [0:1] $end\n"
                         "$var wire 2 \" off[4:3] $end\n$enddefinitions $end\n"
                         "#0 b10 ! b01 \"\n#5 b00 ! b00 \"\n");
    auto c = collectFile(p, {"up[0]", "up[1]", "off[3]", "off[4]"});
    EXPECT_EQ(c.initial, (std::vector<std::uint8_t>{1, 0, 1, 0}));
    EXPECT_EQ(c.edges, E({{5, 0, 0}, {5, 2, 0}}));
    EXPECT_EQ(c.signals[0].msb, 0);
    EXPECT_EQ(c.signals[0].lsb, 1);
    EXPECT_EQ(vectorRangeText(c.signals[1]), "[4:3]");
    SignalInfo off = c.signals[1];
    EXPECT_EQ(bitAtIndex(off, 2), std::nullopt);
    EXPECT_EQ(bitAtIndex(off, 4), 1);
    SignalInfo plain{"v", "v", 8};
    EXPECT_EQ(bitAtIndex(plain, 7), 7);
    EXPECT_EQ(vectorRangeText(plain), "[7:0]");
}

TEST(VcdReader, ChronoVuStyleDigitIdentifiers) {
    auto p =
        tempCapture("cv.vcd",
                    "$timescale 10 ns $end\n$scope module la8 $end\n$var wire 1 0 Channel_0 $end\n"
                    "$var wire 1 1 Channel_1 $end\n$upscope $end\n$enddefinitions $end\n"
                    "$dumpvars\n00\n11\n$end\n#0\n00\n11\n#7\n10\n01\n");
    auto c = collectFile(p);
    EXPECT_EQ(c.initial, (std::vector<std::uint8_t>{0, 1}));
    EXPECT_EQ(c.edges, E({{7, 0, 1}, {7, 1, 0}}));
}

TEST(VcdReader, AliasedIdentifierFeedsEverySignal) {
    auto p = tempCapture(
        "alias.vcd",
        "$timescale 1ns $end\n$scope module a $end\n$var wire 1 ! clk $end\n$upscope $end\n"
        "$scope module b $end\n$var wire 1 ! clk $end\n$upscope $end\n$enddefinitions $end\n"
        "#0 0!\n#4 1!\n");
    auto c = collectFile(p, {"a.clk", "b.clk"});
    EXPECT_EQ(c.edges, E({{4, 0, 1}, {4, 1, 1}}));
}

TEST(VcdReader, ManyEdgesSpanBlocks) {
    std::string text =
        "$timescale 1ns $end\n$var wire 1 ! a $end\n$var wire 1 \" b $end\n$enddefinitions "
        "$end\n#0 0! 0\"\n";
    const int n = 50000;
    for (int i = 1; i <= n; ++i)
        text += "#" + std::to_string(i) + " " + std::to_string(i & 1) + "! " +
                std::to_string(i & 1) + "\"\n";
    auto c = collectFile(tempCapture("many.vcd", text));
    ASSERT_EQ(c.edges.size(), std::size_t(2 * n));
    for (int i = 0; i < 2 * n; ++i) {
        EXPECT_EQ(c.edges[i].t, i / 2 + 1);
        EXPECT_EQ(c.edges[i].line, std::uint32_t(i & 1));
    }
    EXPECT_EQ(c.end, n);
}

TEST(VcdReader, CrLfLineEndingsAndNoFinalNewline) {
    auto p = tempCapture(
        "crlf.vcd",
        "$timescale 1ns $end\r\n$var wire 1 ! a $end\r\n$enddefinitions $end\r\n#0 0!\r\n#3 1!");
    auto c = collectFile(p);
    EXPECT_EQ(c.edges, E({{3, 0, 1}}));
}

TEST(VcdReader, NoTimestampAtAll) {
    auto c = collectFile(tempCapture(
        "nots.vcd", "$timescale 1ns $end\n$var wire 1 ! a $end\n$enddefinitions $end\n"));
    EXPECT_EQ(c.start, 0);
    EXPECT_EQ(c.end, 0);
    EXPECT_EQ(c.initial, (std::vector<std::uint8_t>{1}));
}

// ---- errors: one line, file:line: what was expected ---------------------------------

std::string err(const std::string& name, const std::string& text) {
    return errorOf(tempCapture(name, text));
}

TEST(VcdReaderErrors, UndeclaredIdentifier) {
    const std::string hdr = "$timescale 1ns $end\n$var wire 1 ! a $end\n$enddefinitions $end\n";
    EXPECT_EQ(err("cap.vcd", hdr + "#0 1!\n#5\n1%x\n"),
              tempDir() + "/cap.vcd:6: value change for undeclared identifier '%x'");
}

TEST(VcdReaderErrors, TimeGoingBackwards) {
    const std::string hdr = "$timescale 1ns $end\n$var wire 1 ! a $end\n$enddefinitions $end\n";
    EXPECT_EQ(err("back.vcd", hdr + "#0 1!\n#200\n0!\n#100 1!\n"),
              tempDir() + "/back.vcd:7: time going backwards (#100 after #200)");
}

TEST(VcdReaderErrors, NoEnddefinitions) {
    EXPECT_EQ(err("noend.vcd", "$timescale 1ns $end\n$var wire 1 ! a $end\n"),
              tempDir() + "/noend.vcd:2: no $enddefinitions (the header never ends)");
}

TEST(VcdReaderErrors, EmptyFile) {
    EXPECT_EQ(err("empty.vcd", ""), tempDir() + "/empty.vcd: empty file");
    EXPECT_EQ(err("blank.vcd", "\n\n  \n"),
              tempDir() + "/blank.vcd: empty file (only blank lines)");
}

TEST(VcdReaderErrors, BinaryGarbage) {
    std::string garbage;
    for (int i = 0; i < 2000; ++i)
        garbage += char((i * 7919) % 256);
    EXPECT_EQ(err("garbage.vcd", garbage), tempDir() +
                                               "/garbage.vcd: unknown format: binary data that is "
                                               "neither VCD, CSV nor a sigrok .sr session");
    const std::string hdr = "$timescale 1ns $end\n$var wire 1 ! a $end\n$enddefinitions $end\n";
    EXPECT_EQ(
        err("garbage2.vcd", hdr + "#0 1!\n\x01\x02\x03\n"),
        tempDir() + "/garbage2.vcd:5: binary data (byte 0x01) where a value change was expected");
    EXPECT_EQ(
        err("garbage3.vcd", hdr + "#0 1!\nhello\n"),
        tempDir() + "/garbage3.vcd:5: expected a value change, #time or $keyword, found 'hello'");
}

TEST(VcdReaderErrors, HugeLine) {
    const std::string hdr = "$timescale 1ns $end\n$var wire 1 ! a $end\n$enddefinitions $end\n";
    std::string text = hdr + "#0 1!\n$comment " + std::string(10 << 20, 'a') + " $end\n";
    EXPECT_EQ(err("huge.vcd", text),
              tempDir() + "/huge.vcd:5: line longer than 1 MiB (not a text capture?)");
}

TEST(VcdReaderErrors, BadHeaderPieces) {
    EXPECT_EQ(
        err("ts.vcd", "$timescale 3 ns $end\n$enddefinitions $end\n"),
        tempDir() + "/ts.vcd:1: expected a $timescale like 1ns, 10 us or 100 ps, found '3ns'");
    EXPECT_EQ(err("var.vcd", "$timescale 1 ns $end\n$var wire ! a $end\n$enddefinitions $end\n"),
              tempDir() + "/var.vcd:2: expected '$var TYPE WIDTH ID NAME $end'");
    EXPECT_EQ(
        err("width.vcd", "$timescale 1 ns $end\n$var wire w ! a $end\n$enddefinitions $end\n"),
        tempDir() + "/width.vcd:2: expected a width in $var, found 'w'");
    EXPECT_EQ(err("time.vcd", "$var wire 1 ! a $end\n$enddefinitions $end\n#12a\n"),
              tempDir() + "/time.vcd:3: expected a time after '#', found '#12a'");
}

TEST(VcdReaderErrors, MissingFile) {
    EXPECT_EQ(errorOf(tempDir() + "/does-not-exist.vcd"),
              tempDir() + "/does-not-exist.vcd: cannot open: No such file or directory");
}

}  // namespace
}  // namespace busdecode::test
