// The VCD reader on long runs of value changes, where its tight loop for `#time` and
// `0!`/`1"` tokens does the bulk and hands anything else to the general tokeniser:
// random mixes of every dialect form against a truth kept by the test itself, and every
// error message (with its line number) deep inside such a run.
#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

#include "capture_util.h"

namespace busdecode::test {
namespace {

const char* const kHeader =
    "$timescale 1ns $end\n$scope module top $end\n"
    "$var wire 1 ! a $end\n$var wire 1 \" b $end\n$var wire 1 # c $end\n"
    "$var wire 4 %& v [3:0] $end\n$var wire 1 $ unused $end\n$var real 1 ' r $end\n"
    "$var wire 1 ( d $end\n$var wire 1 ( d_alias $end\n"
    "$var wire 1 )* e $end\n$var wire 1 +, unused2 $end\n"
    "$upscope $end\n$enddefinitions $end\n";
constexpr int kHeaderLines = 14;

// Selected: a, b, c, v[2], r, d, d_alias (aliases make '(' a multi-target code), e (a
// two-character identifier).
const std::vector<LineRef> kLines = {{0, -1}, {1, -1}, {2, -1}, {3, 2},
                                     {5, -1}, {6, -1}, {7, -1}, {8, -1}};

struct Raw {
    std::vector<std::uint8_t> initial;
    std::vector<Edge> edges;  // as the reader hands them out: no dropping here
    Tick start = 0, end = 0;
};

Raw readRaw(const std::string& path) {
    auto r = openCapture(path, {});
    r->select(kLines);
    Raw out;
    out.initial = r->initialLevels();
    out.start = r->startTick();
    EdgeBlock b;
    while (r->next(b)) {
        EXPECT_LE(b.edges.size(), kEdgeBlockSize);
        out.edges.insert(out.edges.end(), b.edges.begin(), b.edges.end());
    }
    out.end = r->endTick();
    return out;
}

// Writes a random capture in a random mix of dialect forms and keeps the truth.
struct Mix {
    std::string text = kHeader;
    std::vector<std::uint8_t> initial;
    std::vector<Edge> truth;
    Tick first = 0, last = 0;
};

// What separates two tokens: mostly a newline, sometimes CRLF, spaces, a tab or a blank line.
std::string randomSeparator(std::mt19937& rng) {
    switch (rng() % 12u) {
        case 0:
            return "\r\n";
        case 1:
            return "  ";
        case 2:
            return "\t";
        case 3:
            return "\n\n";
        case 4:
        case 5:
        case 6:
            return " ";
        default:
            return "\n";
    }
}

Mix randomMix(std::uint32_t seed, Tick t0, int stamps) {
    std::mt19937 rng(seed);
    auto pick = [&](int n) { return int(rng() % unsigned(n)); };
    Mix m;
    std::vector<std::uint8_t> level(kLines.size(), 1);  // before any level: 1
    int vec = 0b1111;
    Tick t = t0;
    m.first = t0;
    auto change = [&](std::size_t line, std::uint8_t v, bool initial) {
        if (level[line] != v && !initial) m.truth.push_back({t, std::uint32_t(line), v});
        level[line] = v;
    };
    for (int i = 0; i < stamps; ++i) {
        const bool initial = i == 0;
        m.text += "#" + std::to_string(t);
        const int n = initial ? 8 : pick(4);  // (the initial row: one of each of 0..7)
        for (int k = 0; k < n; ++k) {
            m.text += randomSeparator(rng);
            const int what = initial ? k : pick(24);
            const std::uint8_t v = std::uint8_t(pick(2));
            if (what < 3 || what >= 14) {  // a plain scalar: the bulk
                const int s = what < 3 ? what : pick(3);
                m.text += char('0' + v);
                m.text += char('!' + s);
                change(std::size_t(s), v, initial);
            } else if (what == 3) {  // x or z keeps the level
                m.text += pick(2) ? "x" : "Z";
                m.text += char('!' + pick(3));
            } else if (what == 4) {  // a vector: bit 2 is a line
                vec = pick(16);
                m.text += "b";
                for (int bit = 3; bit >= 0; --bit)
                    m.text += char('0' + ((vec >> bit) & 1));
                m.text += " %&";
                change(3, std::uint8_t((vec >> 2) & 1), initial);
            } else if (what == 5) {  // a real: nonzero reads 1
                m.text += v ? "r2.5 '" : "r0 '";
                change(4, v, initial);
            } else if (what == 6) {  // an unselected scalar
                m.text += std::string(1, char('0' + v)) + "$";
            } else if (what == 7) {  // the aliased code feeds two lines
                m.text += std::string(1, char('0' + v)) + "(";
                change(5, v, initial);
                change(6, v, initial);
            } else if (what == 8) {
                m.text += "$comment long run " + std::to_string(i) + " $end";
            } else if (what == 9) {
                m.text += "$dumpvars";
            } else if (what == 10) {  // `1 !`: the value and identifier apart
                m.text += std::string(1, char('0' + v)) + " \"";
                change(1, v, initial);
            } else if (what == 12) {  // a two-character identifier
                m.text += std::string(1, char('0' + v)) + ")*";
                change(7, v, initial);
            } else if (what == 13) {  // an unselected one
                m.text += std::string(1, char('0' + v)) + "+,";
            } else {  // same level again: no edge
                m.text += std::string(1, char('0' + level[0])) + "!";
            }
        }
        m.text += randomSeparator(rng);
        if (initial) m.initial = level;
        m.last = t;
        // Gaps of every size, so timestamps cross 8 and 16 digits when t0 is near them.
        const int g = pick(10);
        t += g < 6 ? 1 + pick(9) : g < 9 ? pick(100000) : pick(1 << 30);
    }
    return m;
}

TEST(VcdLongRuns, RandomDialectMixesMatchTheTruth) {
    // Timestamps from 0, across 8 digits, and across 16 digits (the tight loop's limit).
    const Tick starts[] = {0, 99'990'000, 9'999'999'000'000'000};
    std::uint32_t seed = 1;
    for (Tick t0 : starts) {
        for (int round = 0; round < 3; ++round, ++seed) {
            SCOPED_TRACE("seed " + std::to_string(seed));
            const Mix m = randomMix(seed, t0, 20000);
            const Raw r = readRaw(tempCapture("mix.vcd", m.text));
            EXPECT_EQ(r.initial, m.initial);
            EXPECT_EQ(r.start, m.first);
            EXPECT_EQ(r.end, m.last);
            ASSERT_EQ(r.edges.size(), m.truth.size());
            for (std::size_t i = 0; i < r.edges.size(); ++i)
                ASSERT_EQ(r.edges[i], m.truth[i]) << "edge " << i;
        }
    }
}

TEST(VcdLongRuns, TimestampsOfEveryLength) {
    // 1 to 17 digits (an Edge holds up to 2^55 - 1 ticks: 17 digits), each also written
    // with leading zeros up to 20 digits, inside a run long enough that the tight loop
    // sees every one of them.
    std::string text = kHeader;
    std::vector<Edge> want;
    std::uint8_t v = 0;
    Tick p10 = 1;
    for (int digits = 1; digits <= 17; ++digits, p10 *= 10) {
        const Tick t = p10 + digits;  // `digits` digits long, increasing
        const std::string plain = std::to_string(t);
        text += "#" + plain + " " + char('0' + v) + "!\n";
        if (digits > 1) want.push_back({t, 0, v});  // the first time is the initial level
        v ^= 1;
        text += "#" + std::string(20 - plain.size(), '0') + plain + "\n" + char('0' + v) + "!\n";
        if (digits > 1) want.push_back({t, 0, v});
        v ^= 1;
    }
    const Tick late = kMaxEdgeTick - 999;  // 17 digits, up to the last tick an Edge holds
    for (int i = 0; i < 1000; ++i)
        text += "#" + std::to_string(late + i) + "\n";
    const Raw r = readRaw(tempCapture("digits.vcd", text));
    EXPECT_EQ(r.edges, want);
    EXPECT_EQ(r.end, kMaxEdgeTick);
}

// A long valid run, then `bad` on line `kHeaderLines + 1 + lines`.
std::string longRunThen(int lines, const std::string& bad) {
    std::string text = kHeader;
    for (int i = 0; i < lines; ++i)
        text += "#" + std::to_string(1000 + i) + " " + char('0' + (i & 1)) + "!\n";
    text += bad + "\n";
    for (int i = 0; i < 100; ++i)  // the run goes on: the bad line is not near its end
        text += "#" + std::to_string(1'000'000 + i) + " " + char('0' + (i & 1)) + "!\n";
    return text;
}

TEST(VcdLongRuns, ErrorsDeepInARunNameTheirLine) {
    const int n = 30000;
    const std::string at = ":" + std::to_string(kHeaderLines + 1 + n) + ": ";
    struct Case {
        std::string bad, what;
    };
    const Case cases[] = {
        {"#500 1!", "time going backwards (#500 after #30999)"},
        // The run's times have five digits: the tight loop takes a time of five as
        // read where it expects it, and must still see what is wrong with one.
        {"#30998 1!", "time going backwards (#30998 after #30999)"},
        {"#3100a 1!", "expected a time after '#', found '#3100a'"},
        {"#a1000 1!", "expected a time after '#', found '#a1000'"},
        {"#31000a 1!", "expected a time after '#', found '#31000a'"},
        {"#12a 1!", "expected a time after '#', found '#12a'"},
        {"# 1!", "expected a time after '#', found '#'"},
        {"1%", "value change for undeclared identifier '%'"},
        // A whole `#time v!` line of the run's length, taken in one test of its shape
        // (capture/vcd_time_line.h) but for its identifier, and a time of the run's
        // length going backwards on such a line.
        {"#31000 1%", "value change for undeclared identifier '%'"},
        {"#30000 1!", "time going backwards (#30000 after #30999)"},
        // One past the most an Edge holds (core/edge.h), and far past it.
        {"#36028797018963968", "time beyond 2^55 - 1 ticks (36028797018963967)"},
        {"#4611686018427387905", "time beyond 2^55 - 1 ticks (36028797018963967)"},
        {"#99999999999999999999999", "time beyond 2^55 - 1 ticks (36028797018963967)"},
        {"1!\x01", "binary data (byte 0x01) where a value change was expected"},
        {"hello", "expected a value change, #time or $keyword, found 'hello'"},
        {"b1x0", "expected an identifier after the value 'b1x0'"},
    };
    for (const auto& c : cases) {
        SCOPED_TRACE(c.bad);
        const std::string p = tempCapture("deep.vcd", longRunThen(n, c.bad));
        EXPECT_EQ(errorOf(p), p + at + c.what);
    }
}

TEST(VcdLongRuns, CrLfAndBlankRunsCountLines) {
    // Line numbers stay right through CRLF ends and blank lines inside a long run.
    std::string text = kHeader;
    int line = kHeaderLines;
    for (int i = 0; i < 5000; ++i) {
        text += "#" + std::to_string(10 + i) + (i % 3 ? "\r\n" : "\n\n");
        line += i % 3 ? 1 : 2;
    }
    text += "2!\n";
    const std::string p = tempCapture("lines.vcd", text);
    EXPECT_EQ(errorOf(p), p + ":" + std::to_string(line + 1) +
                              ": expected a value change, #time or $keyword, found '2!'");
}

}  // namespace
}  // namespace busdecode::test
