#pragma once
// The bit-level picture of one decoded event, rebuilt from its own fields (the report
// sees events, not edges). Used for the annotated timing diagram of the first faulty
// frame in the HTML report:
//  - an event with `raw` and `bits` (SSI) gives its word MSB first;
//  - a BiSS-C frame with `bits` (position width), or `clocks` to derive it from, gives
//    ACK (+ proc_cycles), Start, CDS, position, nE, nW, the CRC as sent and the stop bit;
//  - anything else has no bit layout, and the diagram shows its fields as boxes.
// The bits are spread evenly over the event's span: a reconstruction, not the edges.
#include <optional>
#include <string>
#include <vector>

#include "core/event.h"

namespace busdecode {

struct BitSegment {
    std::string label;      // "ACK", "POS", "CRC", ...
    std::vector<int> bits;  // levels in transmission order
    bool fault = false;     // the event's errors point at this segment
};

// Empty when the event has no known bit layout.
std::vector<BitSegment> frameLayout(const Event& e);

// Whether a field shows a fault: false "it is right" bools (`*_ok`, `*_match`,
// `consistent`), active nE/nW, or the CRC of a frame with a `crc` error.
bool fieldShowsFault(const Event& e, const Field& f);

}  // namespace busdecode
