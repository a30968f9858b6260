#include "signal_section.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "html_report.h"
#include "sinks/event_format.h"

namespace busdecode {

namespace {

const std::vector<std::string> kHeads = {"line",        "low",        "high",        "swing",
                                         "threshold",   "hysteresis", "rise median", "rise p99",
                                         "fall median", "fall p99",   "overshoot",   "reversals"};

// The field as a number; NaN when absent, null or not a number.
double numberOf(const Event& e, const char* key) {
    const Value* v = e.get(key);
    return v ? asDouble(*v) : NAN;
}

std::string volts(const Event& e, const char* key) {
    const double x = numberOf(e, key);
    return std::isfinite(x) ? fmt::format("{:.3g} V", x) : "-";
}

std::string nanoseconds(const Event& e, const char* key) {
    const double x = numberOf(e, key);
    return std::isfinite(x) ? formatDuration(x) : "-";
}

// "1.234 ms to 5.678 ms: SUMMARY": a pair fault's or a gap's line.
std::string spanLine(const Event& e, const Timebase& tb) {
    return fmt::format("{} to {}: {}", formatDuration(tb.toNsF(double(e.start))),
                       formatDuration(tb.toNsF(double(e.end))), e.summary);
}

// A heading and its items, as the text report's indented lines.
std::string textList(const std::string& heading, const std::vector<std::string>& items) {
    std::string out = "  " + heading + "\n";
    for (const auto& item : items)
        out += "    " + item + "\n";
    return out;
}

// A heading and its items as HTML: a paragraph and a list (none for no items).
std::string htmlList(const std::string& heading, const std::vector<std::string>& items) {
    std::string h = fmt::format("<p>{}</p>\n", htmlEscape(heading));
    if (items.empty()) return h;
    h += "<ul>\n";
    for (const auto& item : items)
        h += fmt::format("<li>{}</li>\n", htmlEscape(item));
    return h + "</ul>\n";
}

std::string fieldText(const Event& e, const char* key) {
    const Value* v = e.get(key);
    if (const auto* s = v ? std::get_if<std::string>(v) : nullptr) return *s;
    const double x = numberOf(e, key);
    return std::isfinite(x) ? fmt::format("{:.4g}", x) : "-";
}

}  // namespace

bool SignalSection::add(const Event& e, const Timebase& tb) {
    if (e.proto != "capture") return false;
    if (e.type == "signal" && lines_.size() < kMaxLines) {
        lines_.push_back({fieldText(e, "line"), volts(e, "low_v"), volts(e, "high_v"),
                          volts(e, "swing_v"), volts(e, "threshold_v"), volts(e, "hysteresis_v"),
                          nanoseconds(e, "rise_median_ns"), nanoseconds(e, "rise_p99_ns"),
                          nanoseconds(e, "fall_median_ns"), nanoseconds(e, "fall_p99_ns"),
                          fieldText(e, "overshoot_pct") + " %", fieldText(e, "reversals")});
    } else if (e.type == "pair_fault") {
        faults_.add(e, tb);
    } else if (e.type == "samples_dropped") {
        gaps_.add(e, tb);
        if (const Value* n = e.get("samples"))
            dropped_samples_ += std::uint64_t(std::max<std::int64_t>(0, asInt(*n)));
    } else if (e.type == "segment_gap") {
        segment_gaps_.add(e, tb);
    }
    return true;
}

void SignalSection::Stretches::add(const Event& e, const Timebase& tb) {
    if (first.size() < kMaxFaults) first.push_back(spanLine(e, tb));
    ++count;
}

std::string SignalSection::segmentGapsHeading() const {
    return fmt::format("Not recorded (dead time between segments): {} gaps", segment_gaps_.count);
}

std::string SignalSection::gapsHeading() const {
    return fmt::format("Samples dropped (live run, decoding fell behind): {} in {} gaps",
                       dropped_samples_, gaps_.count);
}

std::string SignalSection::text() const {
    if (empty()) return "";
    std::vector<std::size_t> width(kHeads.size());
    for (std::size_t c = 0; c < kHeads.size(); ++c) {
        width[c] = kHeads[c].size();
        for (const auto& row : lines_)
            width[c] = std::max(width[c], row[c].size());
    }
    auto row = [&](const std::vector<std::string>& cells) {
        std::string s = " ";
        for (std::size_t c = 0; c < cells.size(); ++c)
            s += fmt::format(" {:<{}}", cells[c], width[c]);
        while (!s.empty() && s.back() == ' ')
            s.pop_back();
        return s + "\n";
    };
    std::string out =
        lines_.empty() ? "\nSignal\n" : "\nSignal quality (analog lines; rise and fall 10-90 %)\n";
    if (!lines_.empty()) out += row(kHeads);
    for (const auto& r : lines_)
        out += row(r);
    // A logic capture's live gaps alone: no pair fault to count.
    if (!lines_.empty() || faults_.count)
        out += textList("pair faults: " + std::to_string(faults_.count), faults_.first);
    if (gaps_.count) out += textList(gapsHeading(), gaps_.first);
    if (segment_gaps_.count) out += textList(segmentGapsHeading(), segment_gaps_.first);
    return out;
}

std::string SignalSection::html() const {
    if (empty()) return "";
    std::string h = "<h2>Signal quality</h2>\n";
    if (!lines_.empty()) {
        h += "<table><tr>";
        for (const auto& head : kHeads)
            h += fmt::format("<th>{}</th>", htmlEscape(head));
        h += "</tr>\n";
        for (const auto& r : lines_) {
            h += "<tr>";
            for (const auto& cell : r)
                h += fmt::format("<td>{}</td>", htmlEscape(cell));
            h += "</tr>\n";
        }
        h += "</table>\n<p>Rise and fall times between 10 and 90 % of the swing.</p>\n";
    }
    if (!lines_.empty() || faults_.count)
        h += htmlList("Pair faults: " + std::to_string(faults_.count), faults_.first);
    if (gaps_.count) h += htmlList(gapsHeading(), gaps_.first);
    if (segment_gaps_.count) h += htmlList(segmentGapsHeading(), segment_gaps_.first);
    return h;
}

}  // namespace busdecode
