#pragma once
// A vector's declared index range (`bus [7:0]`, VHDL's `(0 to 7)` dumped as `[0:7]`, an
// offset `[4:3]`): a bit-select `bus[i]` names a bit by its declared index, as the HDL
// does, not by its place from the LSB.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>

#include "capture_reader.h"

namespace busdecode {

// A `$var`'s reference split the way VCD and FST readers name signals: `data [7:0]` or
// `data[7:0]` is `data` with msb 7, lsb 0 (-1, -1 without a range that spans `width`); a
// 1-bit `bus [3]` keeps its index, `bus[3]`, so it can be mapped by that name. `name` is
// the reference, `after` the token after it ("" when none).
struct VectorName {
    std::string ref;
    int msb = -1, lsb = -1;
};
VectorName splitVectorName(std::string_view name, std::string_view after, int width);

// "[7:0]" -> (msb 7, lsb 0) when it spans `width` bits; nullopt otherwise.
std::optional<std::pair<int, int>> parseVectorRange(std::string_view text, int width);
// The bit of `s`, counted from its LSB, that index `i` names: within its declared range,
// or 0 .. width-1 when it declares none; nullopt outside.
std::optional<int> bitAtIndex(const SignalInfo& s, std::int64_t i);
// How a vector's bits are named, "[7:0]"; "" for one bit.
std::string vectorRangeText(const SignalInfo& s);
// A signal as listings and messages name it: its full name and range ("top.bus[7:0]");
// a scope column whose title is not its name gives both, the name first ("CH1 (column
// 'CH 1 (V)')"), since the name is what --map and --threshold take.
std::string signalText(const SignalInfo& s);

}  // namespace busdecode
