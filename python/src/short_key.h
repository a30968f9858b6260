#pragma once
// Field keys compared where every event's fields are looked at (read()'s columns, the
// dicts of decode()): keys are a few letters, and two word loads each cost less than a
// call to memcmp, which was a fifth of read()'s column building.
#include <cstdint>
#include <cstring>
#include <string>

namespace busdecode::py {

namespace short_key_detail {
template <class Word>
bool sameEnds(const char* a, const char* b, std::size_t n) {
    Word a0, b0, a1, b1;  // the first and the last sizeof(Word) bytes, overlapping
    std::memcpy(&a0, a, sizeof(Word));
    std::memcpy(&b0, b, sizeof(Word));
    std::memcpy(&a1, a + n - sizeof(Word), sizeof(Word));
    std::memcpy(&b1, b + n - sizeof(Word), sizeof(Word));
    return a0 == b0 && a1 == b1;
}
}  // namespace short_key_detail

inline bool sameKey(const std::string& a, const std::string& b) {
    using short_key_detail::sameEnds;
    const std::size_t n = a.size();
    if (n != b.size()) return false;
    if (n > 16) return std::memcmp(a.data(), b.data(), n) == 0;
    if (n >= 8) return sameEnds<std::uint64_t>(a.data(), b.data(), n);
    if (n >= 4) return sameEnds<std::uint32_t>(a.data(), b.data(), n);
    for (std::size_t i = 0; i < n; ++i)
        if (a[i] != b[i]) return false;
    return true;
}

}  // namespace busdecode::py
