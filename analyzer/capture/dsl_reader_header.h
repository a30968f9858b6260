#pragma once
// A DSView session's `header` member as the .dsl readers need it (dsl_reader.cpp for logic
// sessions, dsl_reader_analog.cpp for oscilloscope and analog ones).
#include <cstdint>
#include <map>
#include <memory>
#include <string>

#include "capture_reader.h"
#include "zip_archive.h"

namespace busdecode {

struct DslHeader {
    int version = 0;
    int mode = -1;  // 0 logic, 1 oscilloscope (DSO), 2 analog
    int bits = 8;   // per DSO/analog sample
    std::uint64_t samples = 0, blocks = 0;
    std::int64_t rate = 0;
    std::map<int, std::string> probes;  // hardware index -> name
    // A DSO/analog probe's indented settings by key with its index (`vDiv0`, `mapMax1`).
    std::map<std::string, std::string> probe_settings;
    std::string wall_clock;  // "trigger time" less "trigger pos" samples
};

// An oscilloscope (`O-<ch>/0`) or analog (`A-0/<block>`) session through the analog layer.
std::unique_ptr<CaptureReader> openDslAnalog(std::unique_ptr<ZipArchive> zip, const DslHeader& h,
                                             const OpenOptions& opts);

}  // namespace busdecode
