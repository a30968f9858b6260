#pragma once
// Numbers appended to a string without a format-string interpreter, for summaries and
// lines written once per word or frame (fmt's parser costs more than the digits).
#include <cstdint>
#include <string>

#include <fmt/format.h>

namespace busdecode {

// Upper-case hexadecimal digits, zero-padded to a minimum width: "{:0{}X}".
inline void appendHex(std::string& out, std::uint64_t v, int min_digits) {
    char buf[16];
    int n = 0;
    do {
        buf[n++] = "0123456789ABCDEF"[v & 0xF];
        v >>= 4;
    } while (v != 0 && n < 16);
    for (int pad = min_digits - n; pad > 0; --pad)
        out += '0';
    while (n > 0)
        out += buf[--n];
}

// Decimal digits: "{}".
template <typename Int>
void appendDecimal(std::string& out, Int v) {
    const fmt::format_int text(v);
    out.append(text.data(), text.size());
}

}  // namespace busdecode
