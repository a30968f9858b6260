#pragma once
// A capture's wall-clock start as files write it ("Mon Feb 12 10:00:00 2024" in a VCD's
// $date, as Icarus, GTKWave and sigrok do), told one way: ISO 8601 without a zone
// ("2024-02-12T10:00:00"), since the files give the recording machine's local time.
#include <string>

namespace busdecode {

// The ISO 8601 form of `text` when it is a date in a known layout; else `text` as given
// (trimmed), so that a date in a layout not known here is still passed on.
std::string wallClockFromText(const std::string& text);

}  // namespace busdecode
