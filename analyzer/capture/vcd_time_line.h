#pragma once
// The shape of a VCD time line from the 16 bytes after its '#', in one load: the time's N
// digits (decimal_scan.h), and whether the line is the one most of a capture is made of,
// a time and one scalar change of a one-character identifier, or the next most common,
// two such changes at the same time (an SPI clock edge and a data line's, say):
//     #<N digits> <0 or 1><identifier>\n
//     #<N digits> <0 or 1><identifier> <0 or 1><identifier>\n
// The VCD reader's tight loop (vcd_reader.cpp, runTimesOf) then takes the whole line
// after one test of its shape, rather than token by token: the separator after the time,
// the value, the separator after the identifier are each a byte load, a table look-up
// and a branch there, about a third of the instructions a line costs.
#include <cstddef>
#include <cstdint>

#include "decimal_scan.h"

namespace busdecode {

enum class TimeLineShape {
    NotDigits,   // one of the N bytes is not a digit
    Digits,      // N digits (the value is right); the rest of the line is not looked at
    OneChange,   // N digits, ' ', '0' or '1', one byte, '\n'
    TwoChanges,  // N digits, then twice ' ', '0' or '1', one byte; then '\n'
};

// At most this many digits leave room for the changes in the 16 bytes read.
inline constexpr int kOneChangeMaxDigits = 12;
inline constexpr int kTwoChangesMaxDigits = 9;

namespace detail {

// 16 bytes, zero but for the given (offset, byte) pairs: a template to compare a line with.
template <int... Pairs>
struct LineBytes {
    alignas(16) char b[16] = {};
    constexpr LineBytes() {
        constexpr int kPairs[] = {Pairs...};
        for (std::size_t i = 0; i + 1 < sizeof...(Pairs); i += 2)
            b[kPairs[i]] = char(kPairs[i + 1]);
    }
};

#if defined(__SSE2__)
// Bit i set iff byte i of `raw`, with `low_bit`'s bits set, equals byte i of `want`.
inline int sameBytes(__m128i raw, const char* low_bit, const char* want) {
    const __m128i lowered =
        _mm_or_si128(raw, _mm_load_si128(reinterpret_cast<const __m128i*>(low_bit)));
    return _mm_movemask_epi8(
        _mm_cmpeq_epi8(lowered, _mm_load_si128(reinterpret_cast<const __m128i*>(want))));
}
#endif

}  // namespace detail

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
        static constexpr detail::LineBytes<N, ' ', N + 1, '1', N + 3, '\n'> kOne;
        static constexpr detail::LineBytes<N + 1, 1> kOneLowBit;
        constexpr int kFixed = (1 << N) | (1 << (N + 1)) | (1 << (N + 3));
        if (((is_digit & kDigits) | (detail::sameBytes(raw, kOneLowBit.b, kOne.b) & kFixed)) ==
            (kDigits | kFixed))
            return TimeLineShape::OneChange;
    }
    if constexpr (N <= kTwoChangesMaxDigits) {
        // The same twice over, the identifiers at N + 2 and N + 5, '\n' at N + 6.
        static constexpr detail::LineBytes<N, ' ', N + 1, '1', N + 3, ' ', N + 4, '1', N + 6, '\n'>
            kTwo;
        static constexpr detail::LineBytes<N + 1, 1, N + 4, 1> kTwoLowBits;
        constexpr int kFixed =
            (1 << N) | (1 << (N + 1)) | (1 << (N + 3)) | (1 << (N + 4)) | (1 << (N + 6));
        if (((is_digit & kDigits) | (detail::sameBytes(raw, kTwoLowBits.b, kTwo.b) & kFixed)) ==
            (kDigits | kFixed))
            return TimeLineShape::TwoChanges;
    }
    return (is_digit & kDigits) == kDigits ? TimeLineShape::Digits : TimeLineShape::NotDigits;
#else
    return digitsOfLength<N>(p, value) ? TimeLineShape::Digits : TimeLineShape::NotDigits;
#endif
}

}  // namespace busdecode
