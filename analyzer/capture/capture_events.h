#pragma once
// The events the capture layer makes itself (proto "capture"), declared as decoders declare
// theirs (core/decoder_info.h), so that read()'s tables type their columns alike.
#include <cstdint>
#include <vector>

#include "core/decoder_info.h"
#include "core/event.h"

namespace busdecode {

// "signal" (signal_quality.cpp), "pair_fault" (differential_pairs.cpp), "samples_dropped",
// "segment_gap" and "no_data" (below).
const std::vector<EventTypeSpec>& captureEventTypes();

// A live run's samples from `first` to `last`, `samples` of them, dropped because decoding
// fell behind the device; the session marks every event reaching into them.
Event samplesDroppedEvent(Tick first, Tick last, std::uint64_t samples);

// The stretch from `last_sample` to `first_sample` that a sequence capture did not record,
// before its segment number `segment` (2, 3, ...); the session marks every event reaching
// into it.
Event segmentGapEvent(Tick last_sample, Tick first_sample, std::uint64_t segment);

// A stretch from `from` to `to` where the capture holds no data for `line` (a signal's full
// name; a Saleae CSV's `X`); the session marks every event of a decoder reading that line
// that reaches into it.
Event noDataEvent(Tick from, Tick to, const std::string& line);

}  // namespace busdecode
