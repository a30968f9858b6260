#pragma once
// Captures that are one row of values per sample at a rate the file does not state
// (Vivado ILA CSV exports, headerless sample lists): the dialects parse their headers
// into columns, this reader turns the rows into edges of the selected lines. One tick
// is one row (timebase 1/--rate).
#include <memory>
#include <string>
#include <vector>

#include "capture_reader.h"
#include "text_source.h"

namespace busdecode {

struct SampleColumns {
    enum class Radix { Binary, Hex, Unsigned };
    std::string dialect;               // for messages and formatName(): "vivado-ila-csv"
    std::vector<SignalInfo> signals;   // one per column read (width = its bits)
    std::vector<std::size_t> columns;  // each signal's field in a row (0-based)
    std::vector<Radix> radix;          // each signal's
    std::size_t fields = 0;            // fields a row has
    bool comma_only = true;            // else runs of spaces, TABs or commas separate fields
};

// Reads the rows after the header `src` has already returned; `rate_hz` from --rate
// (> 0: the dialects check).
std::unique_ptr<CaptureReader> sampleRowsReader(std::unique_ptr<TextSource> src,
                                                SampleColumns columns, double rate_hz);

// The dialects: null when the first lines are not theirs (src untouched), else the
// reader, or an InputError naming the dialect and line.
std::unique_ptr<CaptureReader> openIlaCsv(std::unique_ptr<TextSource>& src, std::string_view head,
                                          const OpenOptions& opts);
std::unique_ptr<CaptureReader> openSampleList(std::unique_ptr<TextSource>& src,
                                              std::string_view head, const OpenOptions& opts);

// A --rate as a timebase; throws naming the file and dialect when there is none.
Timebase rowTimebase(const std::string& file, const std::string& dialect, double rate_hz);

}  // namespace busdecode
