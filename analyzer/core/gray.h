#pragma once
// Reflected binary (Gray) code, as absolute encoders send it.
#include <cstdint>

namespace busdecode {

inline std::uint64_t binaryToGray(std::uint64_t b) {
    return b ^ (b >> 1);
}

// MSB-first XOR chain b[i] = b[i+1] ^ g[i], done with shifts in log2(64) steps.
inline std::uint64_t grayToBinary(std::uint64_t g) {
    g ^= g >> 32;
    g ^= g >> 16;
    g ^= g >> 8;
    g ^= g >> 4;
    g ^= g >> 2;
    g ^= g >> 1;
    return g;
}

}  // namespace busdecode
