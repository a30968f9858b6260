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

Event samplesDroppedEvent(Tick first, Tick last, std::uint64_t samples) {
    Event e;
    e.proto = "capture";
    e.type = "samples_dropped";
    e.start = first;
    e.end = last;
    e.add("samples", std::int64_t(samples));
    e.error("samples_dropped");
    e.summary = fmt::format("{} samples dropped: decoding fell behind the device", samples);
    return e;
}

Event segmentGapEvent(Tick last_sample, Tick first_sample, std::uint64_t segment) {
    Event e;
    e.proto = "capture";
    e.type = "segment_gap";
    e.start = last_sample;
    e.end = first_sample;
    e.add("segment", std::int64_t(segment));
    e.error("segment_gap");
    e.summary = fmt::format("not recorded: the dead time before segment {}", segment);
    return e;
}

Event noDataEvent(Tick from, Tick to, const std::string& line) {
    Event e;
    e.proto = "capture";
    e.type = "no_data";
    e.start = from;
    e.end = to;
    e.add("line", line);
    e.error("no_data");
    e.summary = fmt::format("{}: no data in the capture", line);
    return e;
}

}  // namespace busdecode
