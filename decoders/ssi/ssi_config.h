#pragma once
// The SSI decoder's declaration (roles, options, events) and its options resolved into
// one typed struct, so the state machine never parses text.
#include <cstdint>
#include <string>
#include <vector>

#include "core/decoder_info.h"
#include "core/options.h"

namespace busdecode {

enum class SsiParity { None, Even, Odd };

// A named bit of the word (status, alarm, power-fail...), emitted as a field.
struct SsiStatusBit {
    std::string name;
    int bit = 0;  // bit number in `raw` (0 = LSB)
};

struct SsiConfig {
    int bits = 25;  // bits per word, the lead bit included
    int st_bits = 16;
    int mt_bits = 0;
    bool gray = false;
    double tm_us = 20;
    bool lead = false;           // the level at the first sampling edge is a bit (POSITAL)
    bool lsb_first = false;      // first bit on the wire is raw bit 0 (digital calipers)
    bool sample_rising = false;  // the master samples on rising clock edges
    SsiParity parity = SsiParity::None;
    bool parity_msb = false;  // parity is raw's top bit rather than bit 0
    int pos_shift = 0;        // bits below the position field (trailing parity/alarm bits)
    std::vector<SsiStatusBit> status;
    bool delay_auto = false;
    double delay_ns = 0;  // sample this long after each sampling edge
    int ring_gap = 1;     // zero bits between repeats of multiple transmission
    double clock_min_hz = 50e3;
    double clock_max_hz = 2e6;
    double tm_min_us = 10;
    double tm_max_us = 40;
    double gap_bits = 3;  // clock idle for this many periods ends a frame
    bool summary = true;  // emit a `summary` event at the end of the capture

    // Bits that follow the lead bit: the encoder's own word, what repeats carry.
    int dataBits() const { return bits - (lead ? 1 : 0); }
    // Raw bit number of the i-th bit of a word in wire order.
    int bitIndex(int i) const { return lsb_first ? i : bits - 1 - i; }
    // Mask of raw without the lead bit (what a repeat or a re-read must reproduce).
    std::uint64_t dataMask() const;

    // Throws InputError on contradictory widths or a bad status_bits list.
    static SsiConfig fromOptions(const Options& o);
};

const DecoderInfo& ssiInfo();

}  // namespace busdecode
