#pragma once
// Numbers appended to a string without a format-string interpreter, for summaries and
// lines written once per word or frame (fmt's parser costs more than the digits).
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
    ShortLine& dec(std::int64_t v) {
        const fmt::format_int digits(v);
        return text(std::string_view(digits.data(), digits.size()));
    }
    ShortLine& dec(std::uint64_t v) {
        const fmt::format_int digits(v);
        return text(std::string_view(digits.data(), digits.size()));
    }
    ShortLine& dec(int v) { return dec(std::int64_t(v)); }
    // As appendHex.
    ShortLine& hex(std::uint64_t v, int min_digits) {
        char buf[16];
        const char* digits = detail::hexDigits(buf + 16, v);
        const std::size_t n = std::size_t(buf + 16 - digits);
        if (min_digits > int(n) && std::size_t(min_digits) - n <= kCapacity - n_) {
            std::memset(buf_ + n_, '0', std::size_t(min_digits) - n);
            n_ += std::size_t(min_digits) - n;
        }
        return text(std::string_view(digits, n));
    }
    std::string_view view() const { return {buf_, n_}; }

private:
    char buf_[kCapacity];
    std::size_t n_ = 0;
};

}  // namespace busdecode
