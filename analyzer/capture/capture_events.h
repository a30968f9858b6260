#pragma once
// The events the capture layer makes itself (proto "capture"), declared as decoders declare
// theirs (core/decoder_info.h), so that read()'s tables type their columns alike.
#include <vector>

#include "core/decoder_info.h"

namespace busdecode {

// "signal" (signal_quality.cpp) and "pair_fault" (differential_pairs.cpp).
const std::vector<EventTypeSpec>& captureEventTypes();

}  // namespace busdecode
