#include "waveform_svg.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <optional>

#include <fmt/format.h>

#include "sample_plan.h"
#include "sinks/event_format.h"
#include "sinks/xml_escape.h"
#include "svg_plot.h"

namespace busdecode {

namespace {

std::string num(double v) {
    return fmt::format("{:.1f}", v);
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

// An analog line's voltage between `top` and `bottom` (y), with its threshold and the
// hysteresis band around it, scaled to the range seen; `x` maps ns to the plot.
template <typename ToX>
std::string voltageTrace(const LineWave& l, const Timebase& tb, ToX x, double left, double right,
                         double top, double bottom) {
    const float band = l.hysteresis / 2;
    float vmin = l.threshold - band, vmax = l.threshold + band;
    for (const auto& [t, v] : l.trace) {
        vmin = std::min(vmin, v);
        vmax = std::max(vmax, v);
    }
    const double span = std::max(double(vmax - vmin), 1e-6);
    auto y = [&](double v) { return bottom - (v - vmin) / span * (bottom - top); };
    std::string s = fmt::format(
        R"(<rect class="hysteresis" data-role="{}" x="{}" y="{}" width="{}" height="{}" fill="#ffe0b2" opacity="0.6"/>)",
        xmlEscape(l.role), num(left), num(y(l.threshold + band)), num(right - left),
        num(std::max(y(l.threshold - band) - y(l.threshold + band), 0.5)));
    s += fmt::format(
        R"(<line class="threshold" data-role="{0}" x1="{1}" y1="{2}" x2="{3}" y2="{2}" stroke="#e65100" stroke-dasharray="5 3"/>)",
        xmlEscape(l.role), num(left), num(y(l.threshold)), num(right));
    if (!l.trace.empty()) {
        std::string d;
        for (const auto& [t, v] : l.trace)
            d += fmt::format("{}{},{}", d.empty() ? "M" : " L", num(x(tb.toNsF(double(t)))),
                             num(y(v)));
        s += fmt::format(
            R"(<path class="volt-trace" data-role="{}" d="{}" fill="none" stroke="#37474f" stroke-width="1"/>)",
            xmlEscape(l.role), d);
    }
    for (const double v : {double(vmin), double(vmax)})
        s += fmt::format(
            R"(<text class="volt-tick" x="{}" y="{}" text-anchor="end">{:.3g} V</text>)",
            num(left - 6), num(y(v) + 4), v);
    s += fmt::format(
        R"(<text class="threshold-label" x="{}" y="{}" fill="#e65100" text-anchor="end">threshold {:.3g} V, hysteresis {:.3g} V</text>)",
        num(right - 4), num(y(l.threshold) - 3), l.threshold, l.hysteresis);
    if (!l.trace_complete)
        s += fmt::format(R"(<text x="{}" y="{}" fill="#b71c1c">(earlier samples not kept)</text>)",
                         num(left + 4), num(top + 10));
    return s;
}

// The decoded fields above the bits they came from; `x` maps ns to the plot.
template <typename ToX>
std::string fieldSpans(const SamplePlan& plan, ToX x, double top) {
    std::string s;
    const double half = plan.t_ns.size() > 1 ? (x(plan.t_ns[1]) - x(plan.t_ns[0])) / 2 : 4;
    for (const auto& seg : plan.segments) {
        if (seg.first >= plan.t_ns.size()) break;
        const std::size_t last = std::min(seg.first + seg.count, plan.t_ns.size()) - 1;
        const double xa = x(plan.t_ns[seg.first]) - half, xb = x(plan.t_ns[last]) + half;
        s += fmt::format(
            R"(<rect class="field-span" x="{}" y="{}" width="{}" height="18" fill="{}" stroke="#555"/>)",
            num(xa), num(top + 6), num(std::max(xb - xa, 1.0)), seg.fault ? "#ffcdd2" : "#e3f2fd");
        if (xb - xa > 8.0 * double(seg.label.size()) * 0.8)
            s += fmt::format(
                R"(<text class="field-name" x="{}" y="{}" text-anchor="middle">{}</text>)",
                num((xa + xb) / 2), num(top + 19), xmlEscape(seg.label));
    }
    return s;
}

}  // namespace

std::string waveformSvg(const FrameWave& w, const Timebase& tb,
                        const std::map<std::string, std::string>& options) {
    const Event& e = w.event;
    const double t0 = tb.toNsF(double(e.start));
    const double from = tb.toNsF(double(w.from)), to = tb.toNsF(double(w.to));
    const TimeUnit u = timeUnitFor(to - from);
    const SamplePlan plan = planFor(w, tb, options);
    // An analog line has its voltage drawn below its rebuilt levels.
    const double row = 46, trace_row = 70, top_band = plan.segments.empty() ? 10 : 34;
    std::vector<double> tops;
    double lines_height = 0;
    for (const LineWave& l : w.lines) {
        tops.push_back(lines_height);
        lines_height += row + (l.analog ? trace_row : 0);
    }
    const double height = 26 + top_band + lines_height + 50;
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
        const double hi = y0 + tops[i] + 6, lo = hi + 24;
        if (l.analog)
            s +=
                voltageTrace(l, tb, x, plot.left(), plot.right(), lo + 22, lo + 16 + trace_row - 8);
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
    s += fieldSpans(plan, x, plot.top());
    return plot.svg();
}

}  // namespace busdecode
