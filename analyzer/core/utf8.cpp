#include "utf8.h"

namespace busdecode {

std::size_t utf8SequenceLength(const std::string& s, std::size_t i) {
    const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(s[i + k]); };
    const unsigned char b0 = byte(0);
    std::size_t length;
    unsigned char low = 0x80, high = 0xBF;  // the range of the second byte
    if (b0 >= 0xC2 && b0 <= 0xDF) {
        length = 2;
    } else if (b0 >= 0xE0 && b0 <= 0xEF) {
        length = 3;
        if (b0 == 0xE0) low = 0xA0;   // no overlong form
        if (b0 == 0xED) high = 0x9F;  // no surrogates
    } else if (b0 >= 0xF0 && b0 <= 0xF4) {
        length = 4;
        if (b0 == 0xF0) low = 0x90;   // no overlong form
        if (b0 == 0xF4) high = 0x8F;  // at most U+10FFFF
    } else {
        return 0;
    }
    if (s.size() - i < length) return 0;
    if (byte(1) < low || byte(1) > high) return 0;
    for (std::size_t k = 2; k < length; ++k)
        if (byte(k) < 0x80 || byte(k) > 0xBF) return 0;
    return length;
}

std::size_t appendUtf8OrReplacement(std::string& out, const std::string& s, std::size_t i) {
    const std::size_t length = utf8SequenceLength(s, i);
    if (length == 0) {
        out += "\xEF\xBF\xBD";
        return 1;
    }
    out.append(s, i, length);
    return length;
}

}  // namespace busdecode
