#include "crc.h"

namespace busdecode {

BitCrc BitCrc::fromFullPoly(std::uint32_t full_poly, std::uint32_t init, bool inverted) {
    int width = 0;
    for (std::uint32_t p = full_poly; p > 1; p >>= 1)
        ++width;
    const std::uint32_t mask = width >= 32 ? 0xFFFFFFFFu : ((1u << width) - 1u);
    return BitCrc(width, full_poly & mask, init & mask, inverted ? mask : 0u);
}

std::uint32_t crcOfBits(std::uint64_t bits, int n, int width, std::uint32_t poly,
                        std::uint32_t init, std::uint32_t xorout) {
    BitCrc crc(width, poly, init, xorout);
    crc.pushBits(bits, n);
    return crc.value();
}

}  // namespace busdecode
