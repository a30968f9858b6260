#pragma once
// Writes an in-memory Waveform as a capture file the way real tools do: generators use
// these to make the example captures in captures/ and the inputs of differential tests.
// Files are written atomically (temporary file, then rename).
#include <string>

#include "core/waveform.h"

namespace busdecode {

// VCD with sigrok's dialect (several changes on one timestamp line, `$timescale` from
// the waveform's timebase when it is a power of ten, else 1 ps).
void writeVcd(const Waveform& w, const std::string& path);

enum class CsvDialect {
    SigrokDense,   // `; Channels (n/m): A, B` + `; Samplerate: X` comments, `logic,...` header, one
                   // row per sample
    SaleaeLogic2,  // `Time [s],A,B`, one row per change
    Plain,         // header of names, one row per sample (needs --rate to read back)
};
// Dense dialects need a timebase that is one sample per tick (Timebase::fromSampleRate).
void writeCsv(const Waveform& w, const std::string& path, CsvDialect dialect);

}  // namespace busdecode
