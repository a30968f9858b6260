#pragma once
// Numbers appended to a string without a format-string interpreter, for summaries and
// lines written once per word or frame (fmt's parser costs more than the digits).
#include <algorithm>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>

#include <fmt/format.h>

namespace busdecode {

namespace detail {
// The upper-case hex digits of v, unpadded, written backwards so they end at `end` (16
// bytes at most); returns where they start.
inline char* hexDigits(char* end, std::uint64_t v) {
    char* p = end;
    do {
        *--p = "0123456789ABCDEF"[v & 0xF];
        v >>= 4;
    } while (v != 0);
    return p;
}
}  // namespace detail

// The SI prefix that brings a magnitude below 1000: siPower(12.5e6) = 2, and
// siPrefix(2) = "M"; v / siScale(2) = 12.5. Up to E (10^18).
inline int siPower(double magnitude) {
    int p = 0;
    while (magnitude >= 1000 && p < 6) {
        magnitude /= 1000;
        ++p;
    }
    return p;
}
inline const char* siPrefix(int power) {
    static const char* const kPrefix[] = {"", "k", "M", "G", "T", "P", "E"};
    return kPrefix[power];
}
inline double siScale(int power) {
    double s = 1;
    for (int i = 0; i < power; ++i)
        s *= 1000;
    return s;
}

// Upper-case hexadecimal digits, zero-padded to a minimum width: "{:0{}X}".
inline void appendHex(std::string& out, std::uint64_t v, int min_digits) {
    char buf[16];
    const char* digits = detail::hexDigits(buf + 16, v);
    const int n = int(buf + 16 - digits);
    if (min_digits > n) out.append(std::size_t(min_digits - n), '0');
    out.append(digits, std::size_t(n));
}

// Decimal digits: "{}".
template <typename Int>
void appendDecimal(std::string& out, Int v) {
    const fmt::format_int text(v);
    out.append(text.data(), text.size());
}

// A short line built in a stack buffer, piece by piece without a capacity check and a
// call per piece (literal pieces become plain stores), then handed over at once: for the
// summary of every frame. Pieces that would overflow the buffer are dropped; callers'
// lines are bounded well below kCapacity.
class ShortLine {
public:
    static constexpr std::size_t kCapacity = 256;

    ShortLine& text(std::string_view s) {
        if (s.size() <= kCapacity - n_) {
            std::memcpy(buf_ + n_, s.data(), s.size());
            n_ += s.size();
        }
        return *this;
    }
    // Numbers are written into a scratch buffer, then copied whole (a fixed-size copy is
    // a few stores; one of the digits' own length is a call to memcpy) and only the
    // digits kept: about 125 instructions fewer per BiSS-C frame by callgrind.
    ShortLine& dec(std::uint64_t v) {
        // One digit (nE, nW, CDS, CDM: four of a BiSS-C frame's six decimal numbers) is
        // one store.
        if (v < 10 && n_ < kCapacity) [[likely]] {
            buf_[n_++] = char('0' + v);
            return *this;
        }
        return decDigits(v);
    }
    ShortLine& dec(std::int64_t v) {
        if (v >= 0) return dec(std::uint64_t(v));
        text("-");
        return dec(std::uint64_t(0) - std::uint64_t(v));  // INT64_MIN included
    }
    ShortLine& dec(int v) { return dec(std::int64_t(v)); }
    // As appendHex, with min_digits at most 16 (a 64-bit value's digits).
    ShortLine& hex(std::uint64_t v, int min_digits) {
        char scratch[2 * kNumber];
        std::memset(scratch, '0', kNumber);  // the padding, left of the digits
        char* const end = scratch + kNumber;
        const std::size_t digits = std::size_t(end - detail::hexDigits(end, v));
        const std::size_t n = std::max(digits, std::size_t(std::clamp(min_digits, 1, 16)));
        return number(end - n, n);
    }
    std::string_view view() const { return {buf_, n_}; }

private:
    ShortLine& decDigits(std::uint64_t v) {
        char scratch[2 * kNumber];
        char* const end = scratch + kNumber;
        char* p = end;
        while (v >= 100) {
            p -= 2;
            std::memcpy(p, kPairs + 2 * (v % 100), 2);
            v /= 100;
        }
        if (v >= 10) {
            p -= 2;
            std::memcpy(p, kPairs + 2 * v, 2);
        } else {
            *--p = char('0' + v);
        }
        return number(p, std::size_t(end - p));
    }
    static constexpr std::size_t kNumber = 24;  // at least 20 decimal digits
    // "00" to "99", two characters each.
    static constexpr char kPairs[] =
        "00010203040506070809101112131415161718192021222324252627282930313233343536373839"
        "40414243444546474849505152535455565758596061626364656667686970717273747576777879"
        "8081828384858687888990919293949596979899";
    // Keeps the n characters from `first`, copying kNumber from there: `first` lies in
    // the first half of a scratch buffer of 2 * kNumber, and buf_ has kNumber bytes
    // beyond kCapacity for the copy's tail.
    ShortLine& number(const char* first, std::size_t n) {
        if (n <= kCapacity - n_) {
            std::memcpy(buf_ + n_, first, kNumber);
            n_ += n;
        }
        return *this;
    }

    char buf_[kCapacity + kNumber];
    std::size_t n_ = 0;
};

}  // namespace busdecode
