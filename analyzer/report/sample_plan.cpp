#include "sample_plan.h"

#include <algorithm>
#include <cstdlib>

#include <fmt/format.h>

#include "frame_layout.h"

namespace busdecode {

namespace {

const LineWave* lineOf(const FrameWave& w, const std::string& role) {
    for (const auto& l : w.lines)
        if (l.role == role) return &l;
    return nullptr;
}

std::optional<double> number(const Event& e, const char* key) {
    const Value* v = e.get(key);
    if (!v || isNull(*v) || std::holds_alternative<std::string>(*v)) return std::nullopt;
    return asDouble(*v);
}

std::string option(const std::map<std::string, std::string>& o, const char* key,
                   const char* fallback) {
    auto it = o.find(key);
    return it == o.end() ? fallback : it->second;
}

// The clock edges of `level` inside the event, in ns.
std::vector<double> clockEdges(const FrameWave& w, const Timebase& tb, const std::string& role,
                               int level) {
    std::vector<double> out;
    if (const LineWave* l = lineOf(w, role))
        for (const auto& [t, lv] : l->edges)
            if (lv == level && t >= w.event.start && t <= w.event.end)
                out.push_back(tb.toNsF(double(t)));
    return out;
}

void addSegment(SamplePlan& p, std::string label, std::size_t count, bool fault = false) {
    std::size_t first = 0;
    if (!p.segments.empty()) first = p.segments.back().first + p.segments.back().count;
    if (count) p.segments.push_back({std::move(label), first, count, fault});
}

SamplePlan bisscPlan(const FrameWave& w, const Timebase& tb) {
    SamplePlan p{"ma", "sl"};
    const auto rises = clockEdges(w, tb, "ma", 1);
    const double delay = number(w.event, "line_delay_ns").value_or(0);
    if (auto d = number(w.event, "line_delay_ns"); d && rises.size() > 1) {
        p.delay_ns = *d;
        p.delay_from_ns = rises[1];
    }
    // Rising edge 0 latches (LAT); bit k of the layout is read after rising edge k + 1.
    for (const auto& seg : frameLayout(w.event))
        addSegment(p, seg.label, seg.bits.size(), seg.fault);
    for (std::size_t k = 1; k < rises.size(); ++k)
        p.t_ns.push_back(rises[k] + delay);
    return p;
}

// How long after each sampling edge the SSI decoder read the data line: the delay_ns
// option, or with delay_ns=auto the middle of each bit's window, from the measured data
// delay as the decoder places it. (The event's delay_ns is the measured delay, which the
// decoder applies only when asked to.)
double ssiSampleOffset(const FrameWave& w, const Timebase& tb,
                       const std::map<std::string, std::string>& o,
                       const std::vector<double>& sampling) {
    const std::string delay = option(o, "delay_ns", "0");
    if (delay != "auto") return std::atof(delay.c_str());
    const auto clock_hz = number(w.event, "clock_hz");
    if (!clock_hz || *clock_hz <= 0) return 0;
    const double period = 1e9 / *clock_hz;
    const bool rising = option(o, "sample_edge", "falling") == "rising";
    const auto launches = clockEdges(w, tb, "clk", 1);
    double to_sample = 0;
    std::size_t n = 0;
    for (std::size_t k = 0; k + 1 < sampling.size() && k < launches.size(); ++k, ++n)
        to_sample += sampling[k + 1] - launches[k];
    to_sample = n > 0 ? to_sample / double(n) : (rising ? period : period / 2);
    return number(w.event, "delay_ns").value_or(0) + period / 2 - to_sample;
}

SamplePlan ssiPlan(const FrameWave& w, const Timebase& tb,
                   const std::map<std::string, std::string>& o) {
    SamplePlan p{"clk", "data"};
    const int level = option(o, "sample_edge", "falling") == "rising" ? 1 : 0;
    auto edges = clockEdges(w, tb, "clk", level);
    const double offset = ssiSampleOffset(w, tb, o, edges);
    const bool lead = option(o, "lead", "0") == "1";
    // Without a lead bit the first sampling edge latches the word: no bit.
    if (!lead && !edges.empty()) {
        p.delay_ns = number(w.event, "delay_ns").value_or(0);
        p.delay_from_ns = edges.front();
        edges.erase(edges.begin());
    }
    for (double t : edges)
        p.t_ns.push_back(t + offset);
    if (p.t_ns.empty()) return p;
    const std::size_t bits = std::size_t(std::max(1, std::atoi(option(o, "bits", "25").c_str())));
    const std::size_t gap = std::size_t(std::atoi(option(o, "ring_gap", "1").c_str()));
    const bool mismatch = w.event.hasError("repeat_mismatch");
    addSegment(p, "DATA", std::min(bits, p.t_ns.size()), w.event.hasError("short_frame"));
    for (int r = 2; p.segments.back().first + p.segments.back().count < p.t_ns.size(); ++r) {
        const std::size_t left = p.t_ns.size() - p.segments.back().first - p.segments.back().count;
        addSegment(p, "gap", std::min(gap, left));
        const std::size_t rest = p.t_ns.size() - p.segments.back().first - p.segments.back().count;
        if (rest == 0) break;
        addSegment(p, fmt::format("repeat {}", r), std::min(bits - (lead ? 1 : 0), rest), mismatch);
    }
    return p;
}

SamplePlan spiPlan(const FrameWave& w, const Timebase& tb,
                   const std::map<std::string, std::string>& o) {
    const bool rising = option(o, "cpol", "0") == option(o, "cpha", "0");
    SamplePlan p{"sclk", lineOf(w, "mosi") ? "mosi" : "miso"};
    p.t_ns = clockEdges(w, tb, "sclk", rising ? 1 : 0);
    addSegment(p, "word", p.t_ns.size(), w.event.hasError("short_frame"));
    return p;
}

// An asynchronous character's slots: start, data, parity, stop (one sample, or two for
// more than one stop bit, as the UART decoder reads them).
struct CharFormat {
    std::size_t bits = 8;
    bool parity = false;
    std::size_t stop_samples = 1;
    double frameBits(double stop) const { return double(1 + bits + parity) + stop; }
};

// Samples mid-bit after the start edge at `start_ns`, with one field per slot group.
void addCharacter(SamplePlan& p, double start_ns, double bit_ns, const CharFormat& f,
                  const std::string& label, bool parity_fault, bool framing_fault) {
    const std::size_t slots = 1 + f.bits + f.parity + f.stop_samples;
    for (std::size_t k = 0; k < slots; ++k)
        p.t_ns.push_back(start_ns + (double(k) + 0.5) * bit_ns);
    addSegment(p, "start", 1);
    addSegment(p, label, f.bits);
    if (f.parity) addSegment(p, "parity", 1, parity_fault);
    addSegment(p, "stop", f.stop_samples, framing_fault);
}

// UART: one character from the event's start edge; its bit time from its length (exact
// with baud=auto too: the decoder ends a character after its frame bits).
SamplePlan uartPlan(const FrameWave& w, const Timebase& tb,
                    const std::map<std::string, std::string>& o) {
    const Value* line = w.event.get("line");
    if (!line || !std::holds_alternative<std::string>(*line)) return {};
    SamplePlan p{"", std::get<std::string>(*line)};
    CharFormat f;
    f.bits = std::size_t(std::clamp(std::atoi(option(o, "bits", "8").c_str()), 5, 9));
    f.parity = option(o, "parity", "none") != "none";
    const double stop = std::atof(option(o, "stop", "1").c_str());
    f.stop_samples = stop > 1 ? 2 : 1;
    const double bit_ns =
        (tb.toNsF(double(w.event.end)) - tb.toNsF(double(w.event.start))) / f.frameBits(stop);
    const auto value = number(w.event, "value");
    addCharacter(p, tb.toNsF(double(w.event.start)), bit_ns, f,
                 value ? fmt::format("0x{:02X}", std::int64_t(*value)) : "data",
                 w.event.hasError("parity"), w.event.hasError("framing"));
    return p;
}

// TMCL: nine 8N1 characters, each from the first start edge after the one before; the
// bit time from the baud option, or with baud=auto from the shortest pulse seen.
SamplePlan tmclPlan(const FrameWave& w, const Timebase& tb,
                    const std::map<std::string, std::string>& o) {
    const bool reply = w.event.type == "reply";
    SamplePlan p{"", lineOf(w, reply ? "module" : "host") ? (reply ? "module" : "host") : "bus"};
    const LineWave* l = lineOf(w, p.data_role);
    if (!l) return {};
    const int start_level = option(o, "invert", "0") == "1" ? 1 : 0;
    double bit_ns = 1e9 / std::max(1.0, std::atof(option(o, "baud", "9600").c_str()));
    if (option(o, "baud", "9600") == "auto") {
        bit_ns = 0;
        for (std::size_t k = 1; k < l->edges.size(); ++k) {
            const double d = tb.toNsF(double(l->edges[k].first - l->edges[k - 1].first));
            if (d > 0 && (bit_ns == 0 || d < bit_ns)) bit_ns = d;
        }
        if (bit_ns == 0) return {};
    }
    const CharFormat f;
    const double end_ns = tb.toNsF(double(w.event.end));
    double free_from = tb.toNsF(double(w.event.start)) - bit_ns / 2;
    for (const auto& [t, level] : l->edges) {
        const double t_ns = tb.toNsF(double(t));
        if (level != start_level || t_ns < free_from || t_ns > end_ns) continue;
        addCharacter(p, t_ns, bit_ns, f, fmt::format("byte {}", p.segments.size() / 3 + 1), false,
                     w.event.hasError("framing"));
        free_from = t_ns + f.frameBits(1) * bit_ns - bit_ns / 2;
    }
    return p;
}

}  // namespace

SamplePlan planFor(const FrameWave& w, const Timebase& tb,
                   const std::map<std::string, std::string>& o) {
    if (w.event.proto == "bissc" && w.event.type == "frame") return bisscPlan(w, tb);
    if (w.event.proto == "ssi" && w.event.type == "frame") return ssiPlan(w, tb, o);
    if (w.event.proto == "spi" && w.event.type == "transfer") return spiPlan(w, tb, o);
    if (w.event.proto == "uart" && w.event.type == "byte") return uartPlan(w, tb, o);
    if (w.event.proto == "tmcl" && (w.event.type == "command" || w.event.type == "reply"))
        return tmclPlan(w, tb, o);
    return {};
}

}  // namespace busdecode
