// A VCD file tokenised in pieces on two threads (SegmentedVcdReader) must read exactly as
// the sequential reader reads it: the same initial levels, the same edges in the same
// order (a repeated value is never an edge, across a cut too), the same end, the same
// error at the same line after the same edges. Pieces of a few bytes cut the file
// everywhere: inside comments that hold `#` lines, between a `$dumpall` and the values it
// repeats, inside CRLF line ends; a short search for the next `#time` line makes most
// pieces fall back to sequential reading, a long one makes none.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <filesystem>
#include <functional>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "capture/segmented_vcd_reader.h"
#include "capture_util.h"
#include "core/options.h"
#include "vcd_pieces.h"  // fuzz/harness: the readings compared, shared with the fuzz target

namespace busdecode::test {
namespace {

using fuzz::sequentialOptions;

void expectSameReading(const std::string& got, const std::string& want, const std::string& what) {
    const std::string difference = fuzz::readingDifference(got, want);
    ASSERT_TRUE(difference.empty()) << what << ": " << difference;
}

std::string sequential(const std::string& path) {
    return fuzz::sequentialVcdReading(path);
}

std::string segmented(const std::string& path, std::uint64_t piece, std::uint64_t search,
                      const std::function<void()>& before_edges = {}) {
    return fuzz::piecesVcdReading(path, piece, search, before_edges);
}

// Every cut: pieces of 1 byte to 4 KiB, searches of 1 byte to 64 KiB.
void expectSameEverywhere(const std::string& path) {
    const std::string want = sequential(path);
    for (std::uint64_t piece : {1, 2, 3, 7, 16, 61, 256, 4096})
        for (std::uint64_t search : {1, 8, 64, 65536})
            ASSERT_NO_FATAL_FAILURE(expectSameReading(
                segmented(path, piece, search), want,
                fmt::format("{} in pieces of {} bytes, search {}", path, piece, search)));
}

enum class Fault { None, Backwards, BadTime, Garbage, NoLastNewline };

// A VCD with what real writers put in one: times on lines of their own or with the
// changes after them (sigrok), repeated times, values repeated (so not edges), x and z,
// vectors with short values, a real, a two-character identifier starting with '#',
// comments with `#` lines in them, $dumpall repeating every value, blank lines; CRLF or
// LF. `fault` puts an error (or a missing last newline) near the end. Without
// `hash_comments`, no comment holds a `#` line: every piece can then be taken as it was
// tokenised, none falls back (the search permitting).
std::string randomVcd(std::mt19937& rng, int times, bool crlf, Fault fault,
                      bool hash_comments = true) {
    auto pick = [&](int n) { return int(rng() % unsigned(n)); };
    std::string s;
    s += "$date today $end\n$timescale 1ns $end\n$scope module top $end\n";
    s += "$var wire 1 ! a $end\n$var wire 1 \" b $end\n$var wire 1 #x c $end\n";
    s += "$var wire 4 % bus [3:0] $end\n$var real 1 & r $end\n$upscope $end\n";
    s += "$enddefinitions $end\n$dumpvars 1! 0\" x#x b0000 % r0 & $end\n";
    const char* ids[] = {"!", "\"", "#x"};
    const char levels[] = {'0', '1', '0', '1', '0', '1', 'x', 'z'};
    std::uint64_t t = 0;
    for (int i = 0; i < times; ++i) {
        if (fault != Fault::None && fault != Fault::NoLastNewline && i == times - 3) {
            if (fault == Fault::Backwards) s += fmt::format("#{}\n", t / 2);
            if (fault == Fault::BadTime) s += "#12abc\n";
            if (fault == Fault::Garbage) s += "q! what\n";
        }
        t += std::uint64_t(pick(4));  // 0: the same time again
        s += fmt::format("#{}", t);
        if (pick(3) == 0) s += fmt::format(" {}{}", levels[pick(8)], ids[pick(3)]);
        s += "\n";
        for (int c = pick(4); c > 0; --c) {
            switch (pick(6)) {
                case 0:
                    s += fmt::format("b{}{}{}{} %\n", pick(2), pick(2), pick(2), pick(2));
                    break;
                case 1:
                    s += pick(2) ? "b1 %\n" : "bx %\n";  // extended: 0001, xxxx
                    break;
                case 2:
                    s += pick(2) ? "r1.5 &\n" : "r0 &\n";
                    break;
                default:
                    s += fmt::format("{}{}\n", levels[pick(8)], ids[pick(3)]);
            }
        }
        switch (pick(25)) {
            case 0:
                s += hash_comments ? "$comment\n#999999 is no time here\n1! nor a change\n$end\n"
                                   : "$comment\n999999 is no time here\n$end\n";
                break;
            case 1:
                s += "$comment one line $end\n";
                break;
            case 2:
                s += "$dumpall 1! 1\" 1#x b1111 % r1 & $end\n";
                break;
            case 3:
                s += "$dumpall\n0!\n0\"\n0#x\n$end\n";
                break;
            case 4:
                s += "\n\n";
                break;
            default:
                break;
        }
    }
    if (fault == Fault::NoLastNewline) s += fmt::format("#{}\n1!", t + 1);
    if (crlf) {
        std::string w;
        for (char c : s) {
            if (c == '\n') w += '\r';
            w += c;
        }
        s = w;
    }
    return s;
}

TEST(SegmentedVcdReader, ReadsRandomCapturesAsTheSequentialReaderDoes) {
    std::mt19937 rng(20261125);
    for (int k = 0; k < 6; ++k) {
        const std::string path =
            tempCapture(fmt::format("random{}.vcd", k),
                        randomVcd(rng, 300, k % 3 == 2, Fault::None, /*hash_comments=*/k >= 3));
        expectSameEverywhere(path);
    }
}

TEST(SegmentedVcdReader, ReportsFaultsAtTheSameLineAfterTheSameEdges) {
    std::mt19937 rng(7);
    for (Fault f : {Fault::Backwards, Fault::BadTime, Fault::Garbage, Fault::NoLastNewline}) {
        const std::string path = tempCapture(fmt::format("fault{}.vcd", int(f)),
                                             randomVcd(rng, 200, f == Fault::BadTime, f, false));
        const std::string want = sequential(path);
        if (f != Fault::NoLastNewline) {
            ASSERT_NE(want.find("error "), std::string::npos) << want;
        }
        expectSameEverywhere(path);
    }
}

TEST(SegmentedVcdReader, LongLinesFallBackOrFailAsTheSequentialReaderDoes) {
    // A comment line longer than the search (pieces after it cannot find their start),
    // then a line longer than 1 MiB (an error).
    std::string body = "$timescale 1 ns $end\n$var wire 1 ! a $end\n$enddefinitions $end\n";
    body += "#0\n1!\n#5\n0!\n$comment " + std::string(200'000, 'c') + " $end\n#10\n1!\n#20\n0!\n";
    const std::string path = tempCapture("long_comment.vcd", body);
    const std::string want = sequential(path);
    for (std::uint64_t piece : {100, 4096, 65536})
        expectSameReading(segmented(path, piece, 1024), want, std::to_string(piece));

    const std::string too_long =
        tempCapture("too_long.vcd", body + "$comment " + std::string(1 << 20, 'c') + " $end\n");
    const std::string error = sequential(too_long);
    ASSERT_NE(error.find("line longer than 1 MiB"), std::string::npos) << error.substr(0, 200);
    for (std::uint64_t piece : {4096, 65536, 1 << 20})
        expectSameReading(segmented(too_long, piece, 1 << 20), error, std::to_string(piece));
}

TEST(SegmentedVcdReader, TakesOverRegularFilesReadOnTwoThreads) {
    std::mt19937 rng(3);
    const std::string path =
        tempCapture("two_threads.vcd", randomVcd(rng, 60000, false, Fault::None));
    ASSERT_GT(std::filesystem::file_size(path), 2 * kPieceBytes);  // several pieces
    OpenOptions two_threads;                                       // the defaults: --threads 2
    EXPECT_TRUE(openCapture(path, two_threads)->readsAhead());
    EXPECT_FALSE(openCapture(path, sequentialOptions())->readsAhead());
    const Collected two = collectFile(path, {}, two_threads);
    const Collected one = collectFile(path, {}, sequentialOptions());
    EXPECT_GT(one.edges.size(), 10000u);
    EXPECT_EQ(two.initial, one.initial);
    EXPECT_EQ(two.start, one.start);
    EXPECT_EQ(two.edges, one.edges);
    EXPECT_EQ(two.end, one.end);
    OpenOptions followed = two_threads;
    followed.follow = true;
    EXPECT_FALSE(openCapture(path, followed)->readsAhead());
}

TEST(SegmentedVcdReader, AFileThatShrinksWhileReadIsAnInputError) {
    // The pieces are mapped (guarded_mapping.h). A read past the file's new end raises
    // SIGBUS, and the page holding the end reads as zeros without one: neither may crash
    // decode or pass for the file's text, and the capture is not whole: an error after
    // the edges of what is left. Cut after decode opened the file, before its first
    // edge: inside a line, near the start, near the end, and 5 bytes before the end (the
    // last piece's mapping then ends in the page that holds the cut: no fault).
    std::mt19937 rng(11);
    const std::string text = randomVcd(rng, 20000, false, Fault::None, false);
    const std::uint64_t size = text.size();
    for (std::uint64_t at : {size / 2, size / 8, size - size / 32, size - 5}) {
        const std::string path = tempCapture("shrinks.vcd", text);
        const std::string got =
            segmented(path, 4096, 65536, [&] { std::filesystem::resize_file(path, at); });
        ASSERT_EQ(std::filesystem::file_size(path), at);
        const std::string error = fmt::format(
            "error {}: truncated while read (ended at byte {} of {})\n", path, at, size);
        ASSERT_GE(got.size(), error.size()) << got;
        EXPECT_EQ(got.substr(got.size() - error.size()), error) << "cut at " << at;
        const std::string left = sequential(path);  // the file as it is now
        const std::string before = got.substr(0, got.size() - error.size());
        EXPECT_EQ(left.compare(0, before.size(), before), 0) << "cut at " << at;
    }
}

}  // namespace
}  // namespace busdecode::test
