#pragma once
// Helpers for SpliceableDecoder::spliceState(): a decoder's fields as 64-bit words, compared for
// equality only. Doubles go in bit for bit (two states that differ in the last bit of a
// period would sample differently one day).
#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>
#include <vector>

namespace busdecode {

class SpliceWords {
public:
    explicit SpliceWords(std::vector<std::uint64_t>& words) : words_(words) {}

    template <class T>
    SpliceWords& operator<<(T v) {
        if constexpr (std::is_same_v<T, double>)
            words_.push_back(std::bit_cast<std::uint64_t>(v));
        else if constexpr (std::is_enum_v<T>)
            words_.push_back(std::uint64_t(v));
        else
            words_.push_back(std::uint64_t(std::int64_t(v)));
        return *this;
    }
    // Its length, then its bytes eight to a word.
    SpliceWords& operator<<(const std::string& s) {
        words_.push_back(s.size());
        for (std::size_t i = 0; i < s.size(); i += 8) {
            std::uint64_t w = 0;
            std::memcpy(&w, s.data() + i, std::min<std::size_t>(8, s.size() - i));
            words_.push_back(w);
        }
        return *this;
    }

private:
    std::vector<std::uint64_t>& words_;
};

}  // namespace busdecode
