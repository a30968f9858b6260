#pragma once
// Unsigned decimal numbers read eight digits at a time (SWAR: one 64-bit load, a digit
// test for all eight bytes, and three multiplies to combine them), or, for the VCD
// reader's times of a known length, up to 15 at once in an SSE2 register. VCD timestamps
// are 6 to 12 digits on every line of a capture; a byte loop spends more on them than on
// everything else the tokeniser does.
#include <bit>
#include <climits>
#include <cstdint>
#include <cstring>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace busdecode {

struct DecimalScan {
    std::uint64_t value = 0;
    const char* end = nullptr;  // first byte after the digits
    int digits = 0;             // how many digits (0: none at the start)
    bool overflow = false;      // beyond 2^62: value is meaningless
};

namespace detail {

// A byte of the result is non-zero iff that byte of w is not '0'..'9', up to the first
// such byte; the bytes after it may be wrong either way. A byte is a digit iff its high
// nibble is 3 both as is and after adding 6 (0x3A..0x3F become 0x40..). A carry out of a
// byte (>= 0xFA) only disturbs the bytes after it, which lie beyond the first non-digit.
inline std::uint64_t nonDigits(std::uint64_t w) {
    constexpr std::uint64_t k30 = 0x3030303030303030ULL, k06 = 0x0606060606060606ULL,
                            kF0 = 0xF0F0F0F0F0F0F0F0ULL;
    return ((w ^ k30) | ((w + k06) ^ k30)) & kF0;
}

// Number of leading bytes of w (memory order) that are '0'..'9', 0..8.
inline int leadingDigits(std::uint64_t w) {
    const std::uint64_t non_digit = nonDigits(w);
    return non_digit ? std::countr_zero(non_digit) / 8 : 8;
}

// The low n bytes set, n = 1..8.
constexpr std::uint64_t lowBytes(int n) {
    return n >= 8 ? ~std::uint64_t(0) : (std::uint64_t(1) << (8 * n)) - 1;
}

// The value of the first n (1..8) digit bytes of w (memory order, little-endian).
inline std::uint64_t digitsValue(std::uint64_t w, int n) {
    std::uint64_t v = (w - 0x3030303030303030ULL) << (8 * (8 - n));  // leading zeros in front
    v = (v * 10) + (v >> 8);
    v = (((v & 0x000000FF000000FFULL) * (100 + (1000000ULL << 32))) +
         (((v >> 16) & 0x000000FF000000FFULL) * (1 + (10000ULL << 32)))) >>
        32;
    return v & 0xFFFFFFFFULL;
}

}  // namespace detail

// 10^0 .. 10^18, every power of ten below 2^63.
inline constexpr std::uint64_t kPow10[19] = {1ULL,
                                             10ULL,
                                             100ULL,
                                             1000ULL,
                                             10000ULL,
                                             100000ULL,
                                             1000000ULL,
                                             10000000ULL,
                                             100000000ULL,
                                             1000000000ULL,
                                             10000000000ULL,
                                             100000000000ULL,
                                             1000000000000ULL,
                                             10000000000000ULL,
                                             100000000000000ULL,
                                             1000000000000000ULL,
                                             10000000000000000ULL,
                                             100000000000000000ULL,
                                             1000000000000000000ULL};

// The common case in two loads: up to 15 digits at p, reading exactly the 16 bytes at p
// (the caller guarantees they are readable; no bounds check). digits == 16 means 16 or
// more: value and end are then meaningless, use scanDecimal.
inline DecimalScan scanDecimal16(const char* p) {
    static_assert(std::endian::native == std::endian::little, "SWAR digit scan is little-endian");
    DecimalScan r;
    std::uint64_t w;
    std::memcpy(&w, p, 8);
    int n = detail::leadingDigits(w);
    std::uint64_t t = n > 0 ? detail::digitsValue(w, n) : 0;
    if (n == 8) {
        std::memcpy(&w, p + 8, 8);
        const int n2 = detail::leadingDigits(w);
        if (n2 > 0) t = t * kPow10[n2] + detail::digitsValue(w, n2);
        n += n2;
    }
    r.value = t;  // below 10^15 < 2^62 when digits < 16
    r.digits = n;
    r.end = p + n;
    return r;
}

namespace detail {

// digitsOfLength<N> below, by SWAR: the portable version.
template <int N>
inline bool digitsOfLengthSwar(const char* p, std::uint64_t& value) {
    std::uint64_t w;
    std::memcpy(&w, p, 8);
    if constexpr (N <= 8) {
        value = digitsValue(w, N);
        return (nonDigits(w) & lowBytes(N)) == 0;
    } else {
        std::uint64_t w2;
        std::memcpy(&w2, p + 8, 8);
        if constexpr (N <= 10) {  // a digit or two more: no second SWAR for them
            value = digitsValue(w, 8);
            for (int i = 0; i < N - 8; ++i)
                value = value * 10 + (((w2 >> (8 * i)) & 0xFF) - '0');
        } else
            value = digitsValue(w, 8) * kPow10[N - 8] + digitsValue(w2, N - 8);
        return (nonDigits(w) | (nonDigits(w2) & lowBytes(N - 8))) == 0;
    }
}

#if defined(__SSE2__)
// digitsOfLengthSse2 on the 16 bytes already loaded: the value of their first N digits,
// and a mask with bit i set iff byte i is a digit (shapeOfTimeLine() tests more bytes of
// the same load).
template <int N>
inline int digitsOfLengthIn(__m128i raw, std::uint64_t& value) {
    const __m128i d = _mm_sub_epi8(raw, _mm_set1_epi8('0'));
    const __m128i nine = _mm_set1_epi8(9);
    const int is_digit = _mm_movemask_epi8(_mm_cmpeq_epi8(_mm_max_epu8(d, nine), nine));
    const __m128i zero = _mm_setzero_si128();
    // pmaddwd's lanes are little-endian: the first (more significant) digit of a pair is
    // the low 16 bits, so its weight comes first.
    const __m128i by10 = _mm_set_epi16(1, 10, 1, 10, 1, 10, 1, 10);
    __m128i pairs;  // 2-digit values in 16-bit lanes, the first digits' first
    if constexpr (N <= 10) {
        // Up to 8 digits fill the low half alone: moved to its top bytes, they make the
        // only pairs (twice over), and the one 8-digit group needs no multiply by 10^8
        // below. Times of 8 digits or fewer are most of a 500 MB capture's
        // (bench/README.md, "-O3 for the code that decodes"). Of 9 or 10 digits, the last
        // 8 go the same way, moved down, and the first one or two are taken from the low
        // bytes alone: times of 9 digits are the rest of it.
        __m128i low8;
        if constexpr (N <= 8)
            low8 = _mm_slli_si128(d, 8 - N);
        else
            low8 = _mm_srli_si128(d, N - 8);
        const __m128i low = _mm_madd_epi16(_mm_unpacklo_epi8(low8, zero), by10);
        pairs = _mm_packs_epi32(low, low);
    } else {
        // The N digits moved to the top bytes, zeros (leading zeros) shifted in below them.
        const __m128i digits = _mm_slli_si128(d, 16 - N);
        pairs = _mm_packs_epi32(_mm_madd_epi16(_mm_unpacklo_epi8(digits, zero), by10),
                                _mm_madd_epi16(_mm_unpackhi_epi8(digits, zero), by10));
    }
    const __m128i quads =  // each <= 9999: packs below cannot saturate
        _mm_madd_epi16(pairs, _mm_set_epi16(1, 100, 1, 100, 1, 100, 1, 100));
    const __m128i eights = _mm_madd_epi16(_mm_packs_epi32(quads, quads),
                                          _mm_set_epi16(1, 10000, 1, 10000, 1, 10000, 1, 10000));
    const std::uint64_t both = std::uint64_t(_mm_cvtsi128_si64(eights));  // first 8, next 8
    if constexpr (N <= 8) {
        value = both & 0xFFFFFFFFULL;
    } else if constexpr (N <= 10) {
        const unsigned first = unsigned(_mm_cvtsi128_si32(d));  // the first digits' bytes
        const std::uint64_t lead =
            N == 9 ? (first & 0xFF) : (first & 0xFF) * 10 + ((first >> 8) & 0xFF);
        value = lead * 100000000ULL + (both & 0xFFFFFFFFULL);
    } else {
        value = (both & 0xFFFFFFFFULL) * 100000000ULL + (both >> 32);
    }
    return is_digit;
}

// digitsOfLength<N> below, in one 16-byte register (SSE2, every x86-64): the digits
// combined in pairs by three multiply-adds (digits -> 2-digit -> 4-digit -> 8-digit
// lanes) and, past 10 digits, one 64-bit multiply. The SWAR version chains two or three 64-bit
// multiplies per time; this one took reading the 500 MB BiSS-C capture alone from 151 to 114 ms
// (bench/README.md, "Times in one SSE2 register").
template <int N>
inline bool digitsOfLengthSse2(const char* p, std::uint64_t& value) {
    const int is_digit =
        digitsOfLengthIn<N>(_mm_loadu_si128(reinterpret_cast<const __m128i*>(p)), value);
    constexpr int kFirstN = (1 << N) - 1;
    return (is_digit & kFirstN) == kFirstN;
}
#endif

}  // namespace detail

// Exactly N digits (1..15) at p, in the VCD reader's tight loop, which knows how many the
// last time had and expects as many: the number's end is then known before its bytes are
// looked at, and the count needs no search. Reads the 16 bytes at p (no bounds check).
// False when one of the N bytes is not a digit; the byte after them is not looked at.
template <int N>
inline bool digitsOfLength(const char* p, std::uint64_t& value) {
    static_assert(N >= 1 && N <= 15, "up to 15 digits: below 10^15 < 2^62");
    static_assert(std::endian::native == std::endian::little, "SWAR digit scan is little-endian");
#if defined(__SSE2__)
    return detail::digitsOfLengthSse2<N>(p, value);
#else
    return detail::digitsOfLengthSwar<N>(p, value);
#endif
}

// Reads the decimal digits starting at p (none is fine), never reading at or past e.
inline DecimalScan scanDecimal(const char* p, const char* e) {
    static_assert(std::endian::native == std::endian::little, "SWAR digit scan is little-endian");
    const char* const start = p;
    DecimalScan r;
    std::uint64_t t = 0;
    for (;;) {
        if (e - p >= 8) {
            std::uint64_t w;
            std::memcpy(&w, p, 8);
            const int n = detail::leadingDigits(w);
            if (n > 0) t = t * kPow10[n] + detail::digitsValue(w, n);
            p += n;
            if (n == 8) continue;
        } else {
            while (p < e && unsigned(*p - '0') < 10)
                t = t * 10 + unsigned(*p++ - '0');
        }
        break;
    }
    r.end = p;
    r.digits = int(p - start);
    r.value = t;
    // Up to 18 digits stay below 10^18 < 2^62 (no wrap above). Longer ones, rare (leading
    // zeros, or a broken file), are redone exactly.
    if (r.digits > 18) {
        t = 0;
        for (const char* q = start; q < p; ++q) {
            if (t > (std::uint64_t(INT64_MAX) - 9) / 10) {  // no wrap below this
                r.overflow = true;
                break;
            }
            t = t * 10 + unsigned(*q - '0');
        }
        r.value = t;
        r.overflow |= t > (std::uint64_t(1) << 62);
    }
    return r;
}

}  // namespace busdecode
