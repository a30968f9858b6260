#include "waveform_svg.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <optional>

#include <fmt/format.h>

#include "frame_layout.h"
#include "sinks/event_format.h"
#include "sinks/xml_escape.h"
#include "svg_plot.h"

namespace busdecode {

namespace {

std::string num(double v) {
    return fmt::format("{:.1f}", v);
}

// Where the decoder read each bit, and which field each bit belongs to.
struct SamplePlan {
    std::string clock_role, data_role;
    std::vector<double> t_ns;  // one per bit, in wire order
    struct Segment {
        std::string label;
        std::size_t first = 0, count = 0;
        bool fault = false;
    };
    std::vector<Segment> segments;
    std::optional<double> delay_ns;  // measured line delay, drawn after `delay_from_ns`
    double delay_from_ns = 0;
};

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

SamplePlan ssiPlan(const FrameWave& w, const Timebase& tb,
                   const std::map<std::string, std::string>& o) {
    SamplePlan p{"clk", "data"};
    const int level = option(o, "sample_edge", "falling") == "rising" ? 1 : 0;
    auto edges = clockEdges(w, tb, "clk", level);
    const double delay = number(w.event, "delay_ns").value_or(0);
    const bool lead = option(o, "lead", "0") == "1";
    // Without a lead bit the first sampling edge latches the word: no bit.
    if (!lead && !edges.empty()) {
        p.delay_ns = delay;
        p.delay_from_ns = edges.front();
        edges.erase(edges.begin());
    }
    for (double t : edges)
        p.t_ns.push_back(t + delay);
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

SamplePlan planFor(const FrameWave& w, const Timebase& tb,
                   const std::map<std::string, std::string>& o) {
    if (w.event.proto == "bissc" && w.event.type == "frame") return bisscPlan(w, tb);
    if (w.event.proto == "ssi" && w.event.type == "frame") return ssiPlan(w, tb, o);
    if (w.event.proto == "spi" && w.event.type == "transfer") return spiPlan(w, tb, o);
    return {};
}

// The line's level at time t (ns).
int levelAt(const LineWave& l, const Timebase& tb, double t_ns) {
    int level = l.level_before;
    for (const auto& [t, lv] : l.edges) {
        if (tb.toNsF(double(t)) > t_ns) break;
        level = lv;
    }
    return level;
}

}  // namespace

std::string waveformSvg(const FrameWave& w, const Timebase& tb,
                        const std::map<std::string, std::string>& options) {
    const Event& e = w.event;
    const double t0 = tb.toNsF(double(e.start));
    const double from = tb.toNsF(double(w.from)), to = tb.toNsF(double(w.to));
    const TimeUnit u = timeUnitFor(to - from);
    const SamplePlan plan = planFor(w, tb, options);
    const double row = 46, top_band = plan.segments.empty() ? 10 : 34;
    const double height = 26 + top_band + row * double(w.lines.size()) + 50;
    std::string title = fmt::format("{} {} at {}{}: {}", e.instance.empty() ? e.proto : e.instance,
                                    e.type, formatDuration(t0), w.faulty ? "" : " (clean)",
                                    e.errors.empty() ? std::string("no errors") : "");
    for (std::size_t i = 0; i < e.errors.size(); ++i)
        title += (i ? ", " : "errors ") + e.errors[i];
    SvgPlot plot(w.faulty ? "waveform faulty" : "waveform clean", 960, height, title,
                 {(from - t0) / u.ns, (to - t0) / u.ns,
                  fmt::format("time from the event's start ({})", u.name)},
                 {0, 1, "lines"});
    plot.hideYTicks();
    auto x = [&](double t_ns) { return plot.x((t_ns - t0) / u.ns); };
    std::string& s = plot.body();
    const double y0 = plot.top() + top_band;
    for (std::size_t i = 0; i < w.lines.size(); ++i) {
        const LineWave& l = w.lines[i];
        const double hi = y0 + row * double(i) + 6, lo = hi + 24;
        std::string d = fmt::format("M{},{}", num(plot.left()), num(l.level_before ? hi : lo));
        for (const auto& [t, lv] : l.edges) {
            const double xe = x(tb.toNsF(double(t)));
            d += fmt::format(" L{0},{1} L{0},{2}", num(xe), num(lv ? lo : hi), num(lv ? hi : lo));
        }
        const int last = l.edges.empty() ? l.level_before : l.edges.back().second;
        d += fmt::format(" L{},{}", num(plot.right()), num(last ? hi : lo));
        s += fmt::format(
            R"(<path class="edges" data-role="{}" d="{}" fill="none" stroke="{}" stroke-width="1.4"/>)",
            xmlEscape(l.role), d, l.role == plan.data_role ? "#0d47a1" : "#1b5e20");
        s += fmt::format(R"(<text class="line-name" x="{}" y="{}" text-anchor="end">{}</text>)",
                         num(plot.left() - 6), num(hi + 16), xmlEscape(l.role));
        if (!l.complete)
            s +=
                fmt::format(R"(<text x="{}" y="{}" fill="#b71c1c">(earlier edges not kept)</text>)",
                            num(plot.left() + 4), num(hi - 2));
        if (l.role != plan.data_role) continue;
        // The sample points on the data line, with the level read there.
        for (double t : plan.t_ns) {
            const double xs = x(t);
            const int bit = levelAt(l, tb, t);
            s += fmt::format(
                R"(<line class="sample" x1="{0}" y1="{1}" x2="{0}" y2="{2}" stroke="#ef6c00" stroke-dasharray="2 2"/>)",
                num(xs), num(hi - 4), num(lo + 4));
            s += fmt::format(
                R"(<circle class="sample-point" cx="{}" cy="{}" r="2.5" fill="#ef6c00"/>)", num(xs),
                num(bit ? hi : lo));
            s += fmt::format(R"(<text class="bit" x="{}" y="{}" text-anchor="middle">{}</text>)",
                             num(xs), num(lo + 15), bit);
        }
        if (plan.delay_ns) {
            const double xa = x(plan.delay_from_ns), xb = x(plan.delay_from_ns + *plan.delay_ns);
            s += fmt::format(
                R"(<path class="line-delay" d="M{0},{2} L{0},{3} L{1},{3}" stroke="#6a1b9a" fill="none"/>)",
                num(xa), num(xb), num(hi - 10), num(hi - 4));
            s += fmt::format(
                R"(<text class="line-delay" x="{}" y="{}" fill="#6a1b9a">line delay {:.0f} ns</text>)",
                num(xb + 3), num(hi - 4), *plan.delay_ns);
        }
    }
    // The decoded fields above the bits they came from.
    const double half = plan.t_ns.size() > 1 ? (x(plan.t_ns[1]) - x(plan.t_ns[0])) / 2 : 4;
    for (const auto& seg : plan.segments) {
        if (seg.first >= plan.t_ns.size()) break;
        const std::size_t last = std::min(seg.first + seg.count, plan.t_ns.size()) - 1;
        const double xa = x(plan.t_ns[seg.first]) - half, xb = x(plan.t_ns[last]) + half;
        s += fmt::format(
            R"(<rect class="field-span" x="{}" y="{}" width="{}" height="18" fill="{}" stroke="#555"/>)",
            num(xa), num(plot.top() + 6), num(std::max(xb - xa, 1.0)),
            seg.fault ? "#ffcdd2" : "#e3f2fd");
        if (xb - xa > 8.0 * double(seg.label.size()) * 0.8)
            s += fmt::format(
                R"(<text class="field-name" x="{}" y="{}" text-anchor="middle">{}</text>)",
                num((xa + xb) / 2), num(plot.top() + 19), xmlEscape(seg.label));
    }
    return plot.svg();
}

}  // namespace busdecode
