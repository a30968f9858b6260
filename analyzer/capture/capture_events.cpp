#include "capture_events.h"

#include <fmt/format.h>

namespace busdecode {

const std::vector<EventTypeSpec>& captureEventTypes() {
    using K = FieldSpec::Kind;
    static const std::vector<EventTypeSpec> types = {
        {"signal",
         "one per analog line: its levels, edge times and reversals",
         {{"line", K::Text},
          {"low_v", K::Number},
          {"high_v", K::Number},
          {"swing_v", K::Number},
          {"threshold_v", K::Number},
          {"hysteresis_v", K::Number},
          {"rise_median_ns", K::Number},
          {"rise_p99_ns", K::Number},
          {"fall_median_ns", K::Number},
          {"fall_p99_ns", K::Number},
          {"rises", K::Int},
          {"falls", K::Int},
          {"overshoot_pct", K::Number},
          {"reversals", K::Int}}},
        {"pair_fault",
         "a differential pair that stopped being complementary",
         {{"pair", K::Text}, {"wire", K::Text}, {"working", K::Text}, {"kind", K::Text}}},
        {"samples_dropped",
         "a live run's samples dropped because decoding fell behind the device",
         {{"samples", K::Int}}},
        {"segment_gap",
         "the dead time between two segments of a sequence capture, not recorded",
         {{"segment", K::Int}}},
        {"no_data", "a stretch where the capture holds no data for a line", {{"line", K::Text}}},
    };
    return types;
}

namespace {

// A stretch whose decoded events are marked: its type is also the error it carries.
Event stretchEvent(const char* type, Tick start, Tick end, const char* key, Value value,
                   std::string summary) {
    Event e;
    e.proto = "capture";
    e.type = type;
    e.start = start;
    e.end = end;
    e.add(key, std::move(value));
    e.error(type);
    e.summary = std::move(summary);
    return e;
}

}  // namespace

Event samplesDroppedEvent(Tick first, Tick last, std::uint64_t samples) {
    return stretchEvent(
        "samples_dropped", first, last, "samples", std::int64_t(samples),
        fmt::format("{} samples dropped: decoding fell behind the device", samples));
}

Event segmentGapEvent(Tick last_sample, Tick first_sample, std::uint64_t segment) {
    return stretchEvent("segment_gap", last_sample, first_sample, "segment", std::int64_t(segment),
                        fmt::format("not recorded: the dead time before segment {}", segment));
}

Event noDataEvent(Tick from, Tick to, const std::string& line) {
    return stretchEvent("no_data", from, to, "line", line,
                        fmt::format("{}: no data in the capture", line));
}

}  // namespace busdecode
