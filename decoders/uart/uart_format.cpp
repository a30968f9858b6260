#include "uart_format.h"

#include <bit>

#include "core/options.h"

namespace busdecode {

Parity parseParity(const std::string& s) {
    if (s == "even") return Parity::Even;
    if (s == "odd") return Parity::Odd;
    if (s == "mark") return Parity::Mark;
    if (s == "space") return Parity::Space;
    if (s == "ignore") return Parity::Ignore;
    return Parity::None;
}

UartFormat UartFormat::fromOptions(const Options& o) {
    UartFormat f;
    if (o.has("baud") && !o.isAuto("baud")) f.baud = o.number("baud");
    if (o.has("bits")) f.bits = int(o.integer("bits"));
    if (o.has("parity")) f.parity = parseParity(o.text("parity"));
    if (o.has("stop")) f.stop_bits = o.number("stop");
    if (o.has("invert")) f.invert = o.flag("invert");
    if (o.has("lsb_first")) f.lsb_first = o.flag("lsb_first");
    return f;
}

bool UartFormat::parityBitFor(std::uint32_t value) const {
    const bool odd_ones = std::popcount(value & ((1u << bits) - 1)) & 1;
    switch (parity) {
        case Parity::Even:
            return odd_ones;  // makes the count of ones even
        case Parity::Odd:
            return !odd_ones;  // makes it odd
        case Parity::Mark:
            return true;
        case Parity::Space:
            return false;
        case Parity::None:
        case Parity::Ignore:
            return false;
    }
    return false;
}

}  // namespace busdecode
