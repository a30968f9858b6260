#pragma once
// A run stopped by SIGINT or SIGTERM before the end of a capture that is not followed:
// what was decoded is only part of the capture, so nothing is reported as if it were
// all of it. An InputError too, so a caller that knows nothing of interruptions still
// ends with one line and exit 2.
#include <cstdint>
#include <string>

#include <fmt/format.h>

#include "options.h"

namespace busdecode {

class Interrupted : public InputError {
public:
    using InputError::InputError;
};

// "NAME: interrupted[ WHEN], after reading N of M bytes" (M when the size is known).
inline std::string interruptedAt(const std::string& name, const std::string& when,
                                 std::uint64_t bytes_read, std::uint64_t bytes_total) {
    const std::string of = bytes_total ? fmt::format(" of {}", bytes_total) : "";
    return fmt::format("{}: interrupted{}, after reading {}{} bytes", name,
                       when.empty() ? "" : " " + when, bytes_read, of);
}

}  // namespace busdecode
