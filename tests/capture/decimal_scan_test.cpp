// The SWAR decimal scans (scanDecimal, and scanDecimal16 and digitsOfLength for the VCD
// reader's tight loop) must agree with a plain digit loop on every length, every
// terminator, buffer ends at every offset, and the 2^62 limit the VCD reader enforces.
#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <string>
#include <utility>

#include "capture/decimal_scan.h"

using namespace busdecode;

namespace {

struct Reference {
    std::uint64_t value = 0;
    std::size_t digits = 0;
    bool overflow = false;
};

Reference reference(const std::string& s) {
    Reference r;
    std::uint64_t t = 0;
    while (r.digits < s.size() && s[r.digits] >= '0' && s[r.digits] <= '9') {
        if (t > (std::uint64_t(INT64_MAX) - 9) / 10) r.overflow = true;
        t = t * 10 + unsigned(s[r.digits] - '0');
        ++r.digits;
    }
    r.value = t;
    r.overflow |= t > (std::uint64_t(1) << 62);
    return r;
}

// scanDecimal16 on s, padded so its 16-byte read stays inside the string: the same
// digits as the plain loop up to 15, or digits == 16 for 16 or more.
void expectSame16(const std::string& s) {
    const Reference want = reference(s);
    const std::string padded = s + std::string(16, '\n');
    const DecimalScan got = scanDecimal16(padded.data());
    if (want.digits >= 16) {
        ASSERT_EQ(got.digits, 16) << s;
        return;
    }
    ASSERT_EQ(std::size_t(got.digits), want.digits) << s;
    ASSERT_EQ(std::size_t(got.end - padded.data()), want.digits) << s;
    ASSERT_EQ(got.value, want.value) << s;
}

void expectSame(const std::string& s) {
    expectSame16(s);
    const Reference want = reference(s);
    const DecimalScan got = scanDecimal(s.data(), s.data() + s.size());
    ASSERT_EQ(std::size_t(got.end - s.data()), want.digits) << s;
    ASSERT_EQ(std::size_t(got.digits), want.digits) << s;
    ASSERT_EQ(got.overflow, want.overflow) << s;
    if (!want.overflow) {
        ASSERT_EQ(got.value, want.value) << s;
    }
}

// digitsOfLength<N> on s, padded for its 16-byte read: true exactly when the first N
// bytes are digits, and then their value.
template <int N>
void expectSameOfLength(const std::string& s) {
    const std::string padded = s + std::string(16, '\n');
    const Reference want = reference(padded.substr(0, N));
    const auto check = [&](const char* version, auto of_length) {
        std::uint64_t value = 0;
        const bool digits = of_length(padded.data(), value);
        ASSERT_EQ(digits, want.digits == std::size_t(N))
            << version << " " << N << " of '" << s << "'";
        if (digits) {
            ASSERT_EQ(value, want.value) << version << " " << N << " of '" << s << "'";
        }
    };
    // The version the reader uses, and each one this machine can run.
    check("digitsOfLength", digitsOfLength<N>);
    check("SWAR", detail::digitsOfLengthSwar<N>);
#if defined(__SSE2__)
    check("SSE2", detail::digitsOfLengthSse2<N>);
#endif
}

template <std::size_t... N>
void expectSameOfEveryLength(const std::string& s, std::index_sequence<N...>) {
    (expectSameOfLength<int(N) + 1>(s), ...);
}

void expectSameOfEveryLength(const std::string& s) {
    expectSameOfEveryLength(s, std::make_index_sequence<15>());
}

}  // namespace

TEST(DecimalScan, EveryLengthAndTerminator) {
    const std::string terminators[] = {"", " ", "\n", "\r\n", " 1!", ":", "/", "a", "\xff", "#"};
    for (int len = 0; len <= 24; ++len) {
        std::string digits;
        for (int i = 0; i < len; ++i)
            digits += char('0' + (i * 7 + 3) % 10);
        for (const auto& term : terminators) {
            expectSame(digits + term);
            expectSameOfEveryLength(digits + term);
        }
    }
}

TEST(DecimalScan, RandomAgainstPlainLoop) {
    std::mt19937_64 rng(12345);
    const std::string alphabet = "0123456789 \n#!:/;@`\x7f\xfa\xff";
    for (int n = 0; n < 200000; ++n) {
        std::string s;
        const int len = int(rng() % 30);
        for (int i = 0; i < len; ++i)
            s += (rng() % 4) ? char('0' + rng() % 10) : alphabet[rng() % alphabet.size()];
        expectSame(s);
        expectSameOfEveryLength(s);
    }
}

TEST(DecimalScan, LargestOfEveryLength) {
    // All nines: the largest value each step of the combining holds (99, 9999, 99999999).
    for (int len = 1; len <= 16; ++len) {
        expectSame(std::string(std::size_t(len), '9'));
        expectSameOfEveryLength(std::string(std::size_t(len), '9'));
        expectSameOfEveryLength(std::string(std::size_t(len), '9') + "0");
    }
}

TEST(DecimalScan, LimitOfTwoToTheSixtySecond) {
    expectSame("4611686018427387904");   // 2^62: accepted
    expectSame("4611686018427387905");   // 2^62 + 1: overflow
    expectSame("9223372036854775807");   // INT64_MAX
    expectSame("18446744073709551616");  // 2^64: would wrap to 0
    expectSame("99999999999999999999999999");
    expectSame("0000000000000000000000000000012");  // leading zeros are not an overflow
    expectSame("999999999999999999");               // 18 digits: the fast path's limit
}

TEST(DecimalScan, OfLengthSeesANonDigitInEveryPlace) {
    // One byte that is not a digit (just below '0', just above '9', and far from both),
    // in every place of a run of digits of every length, and no digit missed or added.
    for (int len = 1; len <= 16; ++len) {
        for (int at = 0; at < len; ++at) {
            for (char odd : {'/', ':', ' ', '\xff', '\xfa', '#'}) {
                std::string s(std::size_t(len), '9');
                s[std::size_t(at)] = odd;
                expectSameOfEveryLength(s);
            }
        }
    }
}
