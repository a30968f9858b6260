#pragma once
// Sample rates as users and files write them ("2.5", "1e6", "24 MHz"), kept exact: the
// timebase of one tick per sample is the rate's own decimal fraction, never a rounding
// (a sigrok 2.5 Hz capture is 0.4 s per tick, not 1/3 s).
#include <optional>
#include <string>
#include <string_view>

#include "time.h"

namespace busdecode {

// What a bus capture can have: slower is a unit mistake, faster has ticks below 1 fs.
inline constexpr double kMinSampleRateHz = 1e-3, kMaxSampleRateHz = 1e15;

struct SampleRate {
    std::optional<Timebase> timebase;  // one tick per sample; empty when not a rate
    std::string problem;               // why not: "is zero", "is out of range (...)", ...
};

// A decimal number of Hz with an optional unit (Hz, kHz, MHz, GHz; any case, spaces
// around) when `units` is set.
SampleRate parseSampleRate(std::string_view text, bool units);

// A rate already read as a number (--rate, rules): its shortest decimal form, exactly.
SampleRate sampleRateOf(double hz);

// What rateArgument() says of a text that is no rate (the Python module says it too).
inline constexpr const char* kRateExpected =
    "expected a positive number of Hz (like 24 MHz, 2.5 Hz or 1e6)";

// `option TEXT` (--rate, or a rules key) as Hz: a positive number in range, bare or with
// a unit as parseSampleRate() takes it, else an InputError naming the option and the text.
double rateArgument(const std::string& option, const std::string& text);

}  // namespace busdecode
