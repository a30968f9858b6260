#pragma once
// The shape of a VCD time line from the 16 bytes after its '#', in one load: the time's N
// digits (decimal_scan.h), and whether the line is the one most of a capture is made of,
// a time and one scalar change of a one-character identifier:
//     #<N digits> <0 or 1><identifier>\n
// The VCD reader's tight loop (vcd_reader.cpp, runTimesOf) then takes the whole line
// after one test of its shape, rather than token by token: the separator after the time,
// the value, the separator after the identifier are each a byte load, a table look-up
// and a branch there, about a third of the instructions a line costs.
#include <cstdint>

#include "decimal_scan.h"

namespace busdecode {

enum class TimeLineShape {
    NotDigits,  // one of the N bytes is not a digit
    Digits,     // N digits (the value is right); the rest of the line is not looked at
    OneChange,  // N digits, ' ', '0' or '1', one byte, '\n'
};

// At most this many digits leave room for the change in the 16 bytes read.
inline constexpr int kOneChangeMaxDigits = 12;

// Reads the 16 bytes at p (no bounds check: the caller guarantees they are readable).
template <int N>
inline TimeLineShape shapeOfTimeLine(const char* p, std::uint64_t& value) {
#if defined(__SSE2__)
    const __m128i raw = _mm_loadu_si128(reinterpret_cast<const __m128i*>(p));
    const int is_digit = detail::digitsOfLengthIn<N>(raw, value);
    constexpr int kDigits = (1 << N) - 1;
    if constexpr (N <= kOneChangeMaxDigits) {
        // ' ' at N, '1' at N + 1 once its low bit is set ('0' or '1'), '\n' at N + 3; the
        // identifier's byte at N + 2 is the caller's to look up.
        alignas(16) static constexpr auto kTemplate = [] {
            struct Bytes {
                char b[16];
            } t{};
            t.b[N] = ' ';
            t.b[N + 1] = '1';
            t.b[N + 3] = '\n';
            return t;
        }();
        alignas(16) static constexpr auto kLowBit = [] {
            struct Bytes {
                char b[16];
            } t{};
            t.b[N + 1] = 1;
            return t;
        }();
        const __m128i lowered =
            _mm_or_si128(raw, _mm_load_si128(reinterpret_cast<const __m128i*>(kLowBit.b)));
        const int same = _mm_movemask_epi8(
            _mm_cmpeq_epi8(lowered, _mm_load_si128(reinterpret_cast<const __m128i*>(kTemplate.b))));
        constexpr int kFixed = (1 << N) | (1 << (N + 1)) | (1 << (N + 3));
        if (((is_digit & kDigits) | (same & kFixed)) == (kDigits | kFixed))
            return TimeLineShape::OneChange;
    }
    return (is_digit & kDigits) == kDigits ? TimeLineShape::Digits : TimeLineShape::NotDigits;
#else
    return digitsOfLength<N>(p, value) ? TimeLineShape::Digits : TimeLineShape::NotDigits;
#endif
}

}  // namespace busdecode
