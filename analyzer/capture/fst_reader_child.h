#pragma once
// The FST reader's child side (fst_api_process.h): fstapi reads the file there and the
// messages below carry what the parent's CaptureReader hands on.
#include <cstdint>
#include <string>

#include "fst_api_process.h"

namespace busdecode {

namespace fst_message {
enum Kind : std::uint8_t {
    Header = 1,  // child: timescale exponent, start, end, count, then (ref, full, width) each
    Select,      // parent: count, then (signal, bit) for each selected line
    Initial,     // child: the selected lines' levels at the first time, a byte each
    Edges,       // child: a block of Edge words
    End,         // child: the last time seen, the count of x/z/u/w/- changes
    Error,       // child: an InputError's text (fstapi's fatal message, times out of range)
};
}

// Reads `path` with fstapi and answers the parent over `channel` until the end.
void serveFst(const std::string& path, const std::string& name, ChildChannel& channel);

}  // namespace busdecode
