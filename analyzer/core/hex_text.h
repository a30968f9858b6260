#pragma once
// Upper-case hexadecimal digits appended to a string, zero-padded to a minimum width:
// "{:0{}X}" without a format-string interpreter, for summaries written once per word.
#include <cstdint>
#include <string>

namespace busdecode {

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

}  // namespace busdecode
