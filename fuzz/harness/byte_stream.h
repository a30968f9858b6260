#pragma once
// Reads structured values from fuzz bytes; past the end everything reads as zero, so
// every input, however short, is a valid program.
#include <cstddef>
#include <cstdint>

namespace busdecode::fuzz {

class ByteStream {
public:
    ByteStream(const std::uint8_t* data, std::size_t size) : p_(data), end_(data + size) {}
    bool empty() const { return p_ >= end_; }
    std::size_t left() const { return empty() ? 0 : std::size_t(end_ - p_); }
    std::uint8_t byte() { return empty() ? 0 : *p_++; }
    // LEB128: 7 bits per byte, low first (at most 10 bytes).
    std::uint64_t varint() {
        std::uint64_t v = 0;
        for (int shift = 0; shift < 70 && !empty(); shift += 7) {
            const std::uint8_t b = *p_++;
            if (shift < 64) v |= std::uint64_t(b & 0x7f) << shift;
            if (!(b & 0x80)) break;
        }
        return v;
    }

private:
    const std::uint8_t* p_;
    const std::uint8_t* end_;
};

}  // namespace busdecode::fuzz
