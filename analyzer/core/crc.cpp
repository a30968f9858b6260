#include "crc.h"

#include <algorithm>

namespace busdecode {

BitCrc BitCrc::fromFullPoly(std::uint32_t full_poly, std::uint32_t init, bool inverted) {
    int width = 0;
    for (std::uint32_t p = full_poly; p > 1; p >>= 1)
        ++width;
    const std::uint32_t mask = width >= 32 ? 0xFFFFFFFFu : ((1u << width) - 1u);
    return BitCrc(width, full_poly & mask, init & mask, inverted ? mask : 0u);
}

FixedLengthCrc::FixedLengthCrc(const BitCrc& crc, int n)
    : n_(std::clamp(n, 1, 128)), bytes_((n_ + 7) / 8), tables_(std::size_t(bytes_)) {
    // Built with BitCrc itself, so that of() agrees with it by construction: the message
    // pushed as its high part, then its low 64 bits.
    const auto crcOf = [&](std::uint64_t low, std::uint64_t high) {
        BitCrc c = crc;
        c.reset();
        if (n_ > 64) c.pushBits(high, n_ - 64);
        c.pushBits(low, n_ > 64 ? 64 : n_);
        return c.value();
    };
    zero_ = crcOf(0, 0);
    // What each message bit adds (linear): n CRCs, and every entry an XOR of them, which
    // keeps a decoder's start quick (the width finder starts one per candidate width).
    for (int j = 0; j < bytes_; ++j) {
        auto& table = tables_[std::size_t(j)];
        table[0] = 0;
        for (int k = 0; k < 8; ++k) {
            const int bit = 8 * j + k;  // from the message's end
            // (A bit past the message's start adds nothing: pushBits() ignores it.)
            const std::uint64_t one = std::uint64_t(1) << (bit % 64);
            const std::uint32_t adds = (bit < 64 ? crcOf(one, 0) : crcOf(0, one)) ^ zero_;
            const std::uint32_t step = 1u << k;
            for (std::uint32_t b = 0; b < step; ++b)
                table[step | b] = table[b] ^ adds;
        }
    }
}

std::uint32_t crcOfBits(std::uint64_t bits, int n, int width, std::uint32_t poly,
                        std::uint32_t init, std::uint32_t xorout) {
    BitCrc crc(width, poly, init, xorout);
    crc.pushBits(bits, n);
    return crc.value();
}

}  // namespace busdecode
