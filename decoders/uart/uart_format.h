#pragma once
// The character format of an asynchronous serial line (the "8N1" part), shared by the
// decoder and the generator so both agree on where every bit sits in a frame.
#include <cstdint>
#include <string>

namespace busdecode {

class Options;

enum class Parity { None, Even, Odd, Mark, Space, Ignore };

struct UartFormat {
    double baud = 9600;
    int bits = 8;  // data bits, 5..9
    Parity parity = Parity::None;
    double stop_bits = 1;  // 0.5, 1, 1.5 or 2
    bool invert = false;   // line idles low (after an RS-232 level shifter, say)
    bool lsb_first = true;

    // Reads baud (unless "auto"), bits, parity, stop, invert, lsb_first.
    static UartFormat fromOptions(const Options& o);

    bool hasParityBit() const { return parity != Parity::None; }
    // Bit slots before the stop bits: start + data + parity.
    int slotsBeforeStop() const { return 1 + bits + (hasParityBit() ? 1 : 0); }
    double frameBits() const { return slotsBeforeStop() + stop_bits; }
    // The level of the parity bit a transmitter sends for `value`.
    bool parityBitFor(std::uint32_t value) const;
    // Value as it appears on the wire order (LSB first or MSB first) -> value.
    std::uint32_t bitAt(std::uint32_t value, int i) const {
        return lsb_first ? (value >> i) & 1u : (value >> (bits - 1 - i)) & 1u;
    }
};

Parity parseParity(const std::string& s);

}  // namespace busdecode
