#pragma once
// Random traffic for the writer/reader round trips: `changes` toggles of clk, data or cs
// (idle 1, 0, 1), each 1 to max_gap ticks after the one before, from tick `first` on; the
// capture ends `tail` ticks after the last change.
#include <cstdint>

#include "core/waveform.h"

namespace busdecode::test {

Waveform randomTraffic(Timebase tb, std::uint32_t seed, int changes, int max_gap, Tick first,
                       Tick tail);

}  // namespace busdecode::test
