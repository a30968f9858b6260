#pragma once
// A generated BiSS-C capture with everything the generator can vary drawn at random, for
// the tests that decode the same traffic two ways and compare.
#include <cstdint>

#include "core/waveform.h"

namespace busdecode::test {

// A capture of `frames` frames with everything the generator can vary drawn at random:
// the sample rate, line delays of up to several bit times, jitter, busy clocks, clocks
// past the stop bit, a slave that takes those for a new request, Hold-CDM, corrupted
// CRCs, frames cut short, and glitches on both lines.
Waveform randomCapture(std::uint32_t seed, int frames);

}  // namespace busdecode::test
