#pragma once
// The BiSS-C decoder's settings, resolved once from the user's options.
#include <cstdint>

#include "core/options.h"

namespace busdecode {

struct BisscSettings {
    int bits = 26;     // data bits between CDS and nE (position and anything else)
    int st_bits = 26;  // single-turn field (LSB aligned)
    int mt_bits = 0;   // multi-turn field above it
    // CRC over data+nE+nW, MSB first; full-notation polynomial (0x43 = x^6+x+1).
    std::uint32_t crc_poly = 0x43;
    int crc_bits = 6;  // 0: no CRC in the frame
    std::uint32_t crc_init = 0;
    bool crc_inverted = true;
    double timeout_min_ns = 0;  // timeout_short below this (0: no check)

    static BisscSettings from(const Options& o);  // throws InputError on inconsistency
};

}  // namespace busdecode
