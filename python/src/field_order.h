#pragma once
// Where every event's fields are looked at (read()'s columns, the dicts of decode()):
// what each field position held last time, so that events of one kind, which list their
// fields in one order, find each field with one comparison of a few letters.
#include <cstdint>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

namespace busdecode::py {

namespace field_order_detail {
template <class Word>
bool sameEnds(const char* a, const char* b, std::size_t n) {
    Word a0, b0, a1, b1;  // the first and the last sizeof(Word) bytes, overlapping
    std::memcpy(&a0, a, sizeof(Word));
    std::memcpy(&b0, b, sizeof(Word));
    std::memcpy(&a1, a + n - sizeof(Word), sizeof(Word));
    std::memcpy(&b1, b + n - sizeof(Word), sizeof(Word));
    return a0 == b0 && a1 == b1;
}
}  // namespace field_order_detail

// Keys are a few letters: two word loads each cost less than a call to memcmp.
inline bool sameKey(const std::string& a, const std::string& b) {
    using field_order_detail::sameEnds;
    const std::size_t n = a.size();
    if (n != b.size()) return false;
    if (n > 16) return std::memcmp(a.data(), b.data(), n) == 0;
    if (n >= 8) return sameEnds<std::uint64_t>(a.data(), b.data(), n);
    if (n >= 4) return sameEnds<std::uint32_t>(a.data(), b.data(), n);
    for (std::size_t i = 0; i < n; ++i)
        if (a[i] != b[i]) return false;
    return true;
}

// The key and what it stood for (a column, a Python string) at each field position.
template <class V>
class FieldOrder {
public:
    // What `key` stood for at `position` last time, or null when another key was there.
    const V* find(const std::string& key, std::size_t position) const {
        if (position < at_.size() && sameKey(at_[position].first, key))
            return &at_[position].second;
        return nullptr;
    }
    const V& remember(const std::string& key, std::size_t position, V v) {
        if (position >= at_.size()) at_.resize(position + 1);
        at_[position] = {key, std::move(v)};
        return at_[position].second;
    }

private:
    std::vector<std::pair<std::string, V>> at_;
};

}  // namespace busdecode::py
