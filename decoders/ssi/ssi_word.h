#pragma once
// From the bits a master sampled in one clock burst to the SSI word: the first
// transmission, the repeats of multiple transmission (ring shift: gap zeros, then the
// word again) and how they compare; then the word's fields. Pure functions, so the
// rules are tested without any waveform.
#include <cstdint>
#include <optional>
#include <vector>

#include "ssi_config.h"

namespace busdecode {

struct SsiWord {
    std::uint64_t raw = 0;  // the first transmission (right-aligned when short)
    int bits = 0;           // bits of it received (cfg.bits unless short)
    bool short_frame = false;
    int repeats = 0;                      // complete transmissions
    int partial_bits = 0;                 // data bits of an incomplete last repeat
    bool repeat_match = true;             // every repeat (and a partial one) equals the first
    bool separator_ok = true;             // the gap bits between repeats read 0
    std::vector<std::int64_t> diff_bits;  // raw bit numbers that differed, ascending
};

// `samples`: the bits in wire order, the non-bit first sample already dropped (lead=0).
SsiWord assembleWord(const std::vector<std::uint8_t>& samples, const SsiConfig& cfg);

struct SsiFields {
    std::uint64_t position = 0;  // Gray-decoded when cfg.gray
    std::uint64_t st = 0;
    std::uint64_t mt = 0;
    std::optional<double> angle;  // none without a single-turn field
    std::optional<bool> parity_ok;
    std::uint64_t status = 0;  // the bits above the position field
};
SsiFields splitFields(std::uint64_t raw, const SsiConfig& cfg);

// Raw bit numbers set in `diff`, ascending.
std::vector<std::int64_t> bitList(std::uint64_t diff);

// The width of the word the encoder repeats in `samples` (wire order, no lead bit): the
// shortest n for which the samples are an n-bit word with some one in it, then `ring_gap`
// zeros and the word again, as far as the burst goes, at least 8 bits of it; 0
// when there is none. A master set to more bits than the encoder has clocks its ring
// shift: 13-bit words read as 25 bits are 13 bits, a zero and 11 bits again.
int ringWidth(const std::vector<std::uint8_t>& samples, int ring_gap);

}  // namespace busdecode
