#pragma once
// A capture's wall-clock start as files write it ("Mon Feb 12 10:00:00 2024" in a VCD's
// $date, as Icarus, GTKWave and sigrok do), told one way: ISO 8601 without a zone
// ("2024-02-12T10:00:00"), since the files give the recording machine's local time. A
// file that stores an instant instead (DSView: milliseconds since 1970) gives UTC, told
// with its milliseconds and a `Z` ("2021-06-02T01:47:40.321Z").
#include <cstdint>
#include <string>
#include <string_view>

namespace busdecode {

// The ISO 8601 form of `text` when it is a date in a known layout; else `text` as given
// (trimmed), so that a date in a layout not known here is still passed on.
std::string wallClockFromText(const std::string& text);

// Milliseconds since 1970-01-01 UTC as ISO 8601 in UTC.
std::string wallClockFromUnixMs(std::int64_t ms);

// sigrok's CSV output names its acquisition's start in a comment:
// "; from Session-emulating driver on Sun Nov 22 06:44:45 2026" -> the date, or "".
std::string wallClockOfSigrokComment(std::string_view comment);

// LeCroy's CSV lists each segment's trigger time: "#1,22-Jan-2015 11:35:11,0" -> the
// first segment's, or "" for any other line.
std::string wallClockOfLecroySegment(std::string_view line);

}  // namespace busdecode
