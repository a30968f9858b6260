// The SWAR decimal scans (scanDecimal, and scanDecimal16 for the VCD reader's tight loop)
// must agree with a plain digit loop on every length, every terminator, buffer ends at
// every offset, and the 2^62 limit the VCD reader enforces.
#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <string>

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

}  // namespace

TEST(DecimalScan, EveryLengthAndTerminator) {
    const std::string terminators[] = {"", " ", "\n", "\r\n", " 1!", ":", "/", "a", "\xff", "#"};
    for (int len = 0; len <= 24; ++len) {
        std::string digits;
        for (int i = 0; i < len; ++i)
            digits += char('0' + (i * 7 + 3) % 10);
        for (const auto& term : terminators)
            expectSame(digits + term);
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
