#pragma once
// How an event is written out: one JSON object (the `jsonl` contract) or one human
// line. Shared by the stdout sinks, the report, verify and the LCM annotation message,
// so every output says exactly the same thing.
#include <cmath>
#include <string>
#include <string_view>

#include "core/event.h"
#include "core/session.h"

namespace busdecode {

// {"proto":..,"type":..,"start_ns":..,"end_ns":..,<fields in order>,"errors":[..]}
std::string eventToJson(const Event& e, const Timebase& tb);
// The same appended to `out` (sinks reuse one buffer: no allocation per event).
void appendEventJson(std::string& out, const Event& e, const Timebase& tb);
// JSON text of one value (numbers as integers when integral, strings escaped).
std::string valueToJson(const Value& v);
// The jsonl mapping, for every writer of events as objects (jsonl, the Python module):
// a decoder's field named like a common key is never written (the keys are the session's).
inline bool isCommonEventKey(std::string_view key) {
    return key == "proto" || key == "type" || key == "start_ns" || key == "end_ns" ||
           key == "errors";
}
// How jsonl writes a double: non-finite as null, whole numbers below 1e15 as integers.
enum class JsonNumber { Null, Integer, Real };
inline JsonNumber jsonNumberKind(double x) {
    if (!std::isfinite(x)) return JsonNumber::Null;
    return x == std::floor(x) && std::fabs(x) < 1e15 ? JsonNumber::Integer : JsonNumber::Real;
}
// "   12.345678 ms  bissc  frame  pos=0x... crc ok  [crc, short_frame]"
std::string eventToText(const Event& e, const Timebase& tb);
void appendEventText(std::string& out, const Event& e, const Timebase& tb);
// A time in ns formatted with a unit that suits it ("12.345 us").
std::string formatDuration(double ns);

}  // namespace busdecode
