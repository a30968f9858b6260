#pragma once
// The arguments decode(), follow() and read() share, checked as `decode` checks its own.
#include <optional>
#include <string>
#include <vector>

#include "capture/capture_reader.h"
#include "event_stream.h"

namespace busdecode::py {

struct CaptureArgs {
    std::string path;
    std::vector<std::string> protos, maps, opts;
    std::optional<double> rate;  // Hz
    // Analog lines: "VOLTS" or "SIGNAL=VOLTS" (--threshold), and --hysteresis VOLTS.
    std::vector<std::string> thresholds;
    std::optional<std::string> hysteresis;
    int threads = 2;
};

// The job for one capture; throws UsageError on a bad rate or thread count, or a bad
// decoder, role or option.
DecodeJob jobFor(const CaptureArgs& a, bool follow);

// Sets the analog lines' --threshold and --hysteresis as `decode` parses them; throws
// UsageError with its message.
void setAnalogOptions(OpenOptions& open, const std::vector<std::string>& thresholds,
                      const std::optional<std::string>& hysteresis);

}  // namespace busdecode::py
