#pragma once
// Collects serial bits into a word, MSB first or LSB first, up to 64 bits; longer
// words keep counting (so a 152-bit burst is seen as 152 bits) but keep only 64.
#include <cstdint>

namespace busdecode {

class BitWord {
public:
    explicit BitWord(bool lsb_first = false) : lsb_first_(lsb_first) {}
    void clear() {
        value_ = 0;
        count_ = 0;
    }
    void push(bool bit) {
        value_ = pushed(value_, count_, bit, lsb_first_);
        ++count_;
    }
    // push() on a word kept elsewhere: `value` holding `count` bits, `bit` pushed on
    // (SPI keeps its words in plain integers, for a loop that holds them in registers).
    static std::uint64_t pushed(std::uint64_t value, int count, bool bit, bool lsb_first) {
        if (!lsb_first) return (value << 1) | std::uint64_t(bit);
        return count < 64 ? value | (std::uint64_t(bit) << count) : value;
    }
    std::uint64_t value() const { return value_; }
    int count() const { return count_; }
    bool overflowed() const { return count_ > 64; }
    void setLsbFirst(bool lsb) { lsb_first_ = lsb; }

private:
    std::uint64_t value_ = 0;
    int count_ = 0;
    bool lsb_first_;
};

// Low n bits of v (n may be 64).
inline std::uint64_t lowBits(std::uint64_t v, int n) {
    return n >= 64 ? v : (v & ((std::uint64_t(1) << n) - 1));
}

}  // namespace busdecode
