// shapeOfTimeLine (capture/vcd_time_line.h), the VCD reader's test of a whole
// `#time v!` (or `#time v! v"`) line in one load: the shape it reports must be exactly what the
// bytes are, for every length of the time, with every byte of the line changed in turn; the time's
// value must be the plain digit loop's.
#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <utility>

#include "capture/vcd_time_line.h"

using namespace busdecode;

namespace {

// The shape by a byte loop: what shapeOfTimeLine<N> must say of `line` (the bytes after
// the '#'), with the value of its first n digits.
std::pair<TimeLineShape, std::uint64_t> reference(const std::string& line, int n) {
    std::uint64_t v = 0;
    for (int i = 0; i < n; ++i) {
        const char c = line[std::size_t(i)];
        if (c < '0' || c > '9') return {TimeLineShape::NotDigits, 0};
        v = v * 10 + std::uint64_t(c - '0');
    }
    const auto at = [&](int i) { return line[std::size_t(i)]; };
    const auto change = [&](int i) {
        return at(i) == ' ' && (at(i + 1) == '0' || at(i + 1) == '1');
    };
    if (n <= kOneChangeMaxDigits && change(n) && at(n + 3) == '\n')
        return {TimeLineShape::OneChange, v};
    if (n <= kTwoChangesMaxDigits && change(n) && change(n + 3) && at(n + 6) == '\n')
        return {TimeLineShape::TwoChanges, v};
    return {TimeLineShape::Digits, v};
}

template <int N>
void expectShape(const std::string& line) {
    std::string padded = line;
    padded.resize(32, 'z');  // shapeOfTimeLine reads 16 bytes, whatever the line's length
    std::uint64_t value = ~std::uint64_t(0);
    const TimeLineShape got = shapeOfTimeLine<N>(padded.data(), value);
    const auto [want, want_value] = reference(padded, N);
    ASSERT_EQ(int(got), int(want)) << "N=" << N << " '" << line << "'";
    if (want != TimeLineShape::NotDigits) {
        EXPECT_EQ(value, want_value) << "N=" << N;
    }
}

// Every byte of `#<N digits> 1!\n` and `#<N digits> 1! 0"\n` (and of the 16 bytes read)
// replaced by each of a few bytes that are, or are almost, what belongs there.
template <int N>
void everyByteChanged() {
    std::string digits;
    for (int i = 0; i < N; ++i)
        digits += char('1' + (i * 7) % 9);
    for (const char* rest : {" 1!\n#", " 0! 1\"\n#"}) {
        const std::string good = digits + rest;
        expectShape<N>(good);
        for (std::size_t at = 0; at < 16; ++at) {
            for (char c : {'0', '9', '/', ':', ' ', '\t', '\r', '\n', '1', '!', 'x', '#', '\xb1'}) {
                std::string s = good;
                s.resize(16, 'z');
                s[at] = c;
                expectShape<N>(s);
            }
        }
    }
}

template <int... N>
void allLengths(std::integer_sequence<int, N...>) {
    (everyByteChanged<N + 1>(), ...);
}

TEST(VcdTimeLine, EveryLengthEveryByte) {
    allLengths(std::make_integer_sequence<int, 15>());
}

TEST(VcdTimeLine, TheFormsItLeavesToTheTokenLoop) {
    // Three changes, a two-character identifier, CRLF, a tab, a value of x: digits only.
    for (const char* rest : {" 1! 0\" 1#\n", " 1!a\n", " 1!\r\n", "\t1!\n", " x!\n", "\n1!\n",
                             " 1! 0\"\r\n", " 1!  0\"\n", " 1! x\"\n"}) {
        SCOPED_TRACE(rest);
        expectShape<8>(std::string("12345678") + rest);
    }
    std::uint64_t v = 0;
    std::string line = "123456789012 1!\n";
    EXPECT_EQ(shapeOfTimeLine<12>(line.data(), v), TimeLineShape::OneChange);
    EXPECT_EQ(v, 123456789012u);
    line = "123456789 1! 0\"\n";
    EXPECT_EQ(shapeOfTimeLine<9>(line.data(), v), TimeLineShape::TwoChanges);
    EXPECT_EQ(v, 123456789u);
    line = "1234567890 1! 0\"\n";  // ten digits: no room for two changes
    EXPECT_EQ(shapeOfTimeLine<10>(line.data(), v), TimeLineShape::Digits);
    // Thirteen digits leave no room for the change in 16 bytes: never OneChange.
    line = "1234567890123 1!\n...";
    EXPECT_EQ(shapeOfTimeLine<13>(line.data(), v), TimeLineShape::Digits);
    EXPECT_EQ(v, 1234567890123u);
}

}  // namespace
