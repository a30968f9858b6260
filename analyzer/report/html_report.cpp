#include "html_report.h"

#include "sinks/xml_escape.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>

#include <fmt/format.h>

#include "core/options.h"
#include "frame_layout.h"
#include "report_format.h"
#include "sinks/event_format.h"
#include "svg_plot.h"
#include "text_report.h"
#include "waveform_svg.h"

namespace busdecode {

namespace {

constexpr const char* kStyle = R"(
body{font-family:system-ui,sans-serif;margin:24px;color:#222;background:#fff}
h1{font-size:22px}h2{font-size:18px;margin-top:28px;border-bottom:1px solid #ccc}
table{border-collapse:collapse;margin:8px 0}td,th{padding:2px 10px;text-align:left}
th{background:#eee}td.n{text-align:right;font-variant-numeric:tabular-nums}
.fault{color:#b00}pre{background:#f6f6f6;padding:8px;overflow-x:auto}
svg{background:#fcfcfc;border:1px solid #ddd;margin:6px 6px 6px 0}
svg text{font-family:monospace;font-size:11px}
)";

std::string esc(const std::string& s) {
    return htmlEscape(s);
}

std::string num(double v) {
    return fmt::format("{:.1f}", v);
}

// A field's values on an axis: the scale to divide by and the title with the unit.
struct FieldAxis {
    double scale = 1;
    std::string title;
};

FieldAxis fieldAxis(const std::string& key, double largest) {
    const auto ends = [&](const char* suffix) {
        const std::string_view sv(suffix);
        return key.size() > sv.size() && key.compare(key.size() - sv.size(), sv.size(), sv) == 0;
    };
    if (ends("_ns") || ends("_us")) {
        const double ns = ends("_us") ? 1e3 : 1;
        const TimeUnit u = timeUnitFor(largest * ns);
        return {u.ns / ns, fmt::format("{} ({})", key, u.name)};
    }
    if (ends("_hz")) {
        const double a = std::fabs(largest);
        if (a >= 1e6) return {1e6, key + " (MHz)"};
        if (a >= 1e3) return {1e3, key + " (kHz)"};
        return {1, key + " (Hz)"};
    }
    return {1, key};
}

// Counts per turn from the decoder's layout (2^st_bits), 0 when unknown.
double countsPerTurn(const std::string& proto, const std::map<std::string, std::string>& o) {
    auto get = [&](const char* k) -> std::optional<std::int64_t> {
        auto it = o.find(k);
        return it == o.end() ? std::nullopt : parseInteger(it->second);
    };
    std::optional<std::int64_t> st = get("st_bits");
    if (!st && proto == "bissc")
        if (auto bits = get("bits")) st = *bits - get("mt_bits").value_or(0);
    if ((proto != "ssi" && proto != "bissc") || !st || *st <= 0 || *st > 62) return 0;
    return std::ldexp(1.0, int(*st));
}

struct TimeAxis {
    double t0 = 0, t1 = 1;
    TimeUnit unit{"ns", 1};
    PlotAxis axis() const {
        return {0, (t1 - t0) / unit.ns,
                fmt::format("time from the capture's start ({})", unit.name)};
    }
    double at(double t_ns) const { return (t_ns - t0) / unit.ns; }
};

TimeAxis captureTime(const CaptureStats& stats, double first_ns, double last_ns) {
    const Timebase& tb = stats.facts().timebase;
    TimeAxis a;
    a.t0 = tb.toNsF(double(stats.facts().start));
    a.t1 = tb.toNsF(double(stats.facts().end));
    if (!(a.t1 > a.t0)) {
        a.t0 = first_ns;
        a.t1 = std::max(last_ns, a.t0 + 1);
    }
    a.unit = timeUnitFor(a.t1 - a.t0);
    return a;
}

// A trace (position or velocity) over time: one vertical stroke per point (its min..max);
// `second_scale` > 0 labels the right-hand axis with the values times it.
std::string traceSvg(const std::string& css, const std::string& title, const std::string& y_title,
                     const PositionTrace& trace, const TimeAxis& ta, const char* colour,
                     double second_scale = 0, const std::string& second_title = "") {
    const auto& pts = trace.points();
    double lo = pts.front().lo, hi = pts.front().hi;
    for (const auto& q : pts) {
        lo = std::min(lo, q.lo);
        hi = std::max(hi, q.hi);
    }
    const double pad = (hi - lo) * 0.05;
    SvgPlot plot(css, 900, 260, title, ta.axis(), {lo - pad, hi + pad, y_title});
    if (second_scale > 0) plot.secondYAxis(second_scale, second_title);
    std::string path;
    for (const auto& q : pts)
        path += fmt::format("{}{},{} L{},{} ", path.empty() ? "M" : "L", num(plot.x(ta.at(q.t_ns))),
                            num(plot.y(q.lo)), num(plot.x(ta.at(q.t_ns))), num(plot.y(q.hi)));
    plot.body() += fmt::format(
        R"(<path class="trace" d="{}" fill="none" stroke="{}" stroke-width="1.2"/>)", path, colour);
    return plot.svg();
}

std::string positionSvgs(const CaptureStats& stats, const std::string& inst,
                         const PositionStats& p) {
    const auto& pts = p.trace.points();
    if (pts.empty()) return "";
    const TimeAxis ta = captureTime(stats, pts.front().t_ns, pts.back().t_ns);
    const std::string wrap =
        p.modulus > 0 ? fmt::format(", unwrapped (the word wraps at {:.0f})", p.modulus) : "";
    std::string s = traceSvg("position", fmt::format("{} position{}", inst, wrap),
                             "position (counts)", p.trace, ta, "#1565c0");
    if (p.velocity.points().empty()) return s;
    // Velocity: counts/s, with rev/min on the right when the counts per turn are known.
    const auto& facts = stats.facts();
    auto opts = facts.options.find(inst);
    const double per_turn = opts == facts.options.end()
                                ? 0
                                : countsPerTurn(inst.substr(0, inst.find('#')), opts->second);
    return s + traceSvg("velocity", fmt::format("{} velocity", inst), "velocity (counts/s)",
                        p.velocity, ta, "#6a1b9a", per_turn > 0 ? 60.0 / per_turn : 0,
                        "velocity (rev/min)");
}

std::string faultsOverTimeSvg(const CaptureStats& stats, const std::string& inst,
                              const TimeCounts& c) {
    if (c.bins().empty()) return "";
    const TimeAxis ta =
        captureTime(stats, c.originNs(), c.originNs() + c.binNs() * double(c.bins().size()));
    // About a hundred bars over the capture, whatever the bins were when it ended.
    std::size_t merge = 1;
    while (c.binNs() * double(merge) * 100 < ta.t1 - ta.t0)
        merge *= 2;
    std::vector<std::uint64_t> bins((c.bins().size() + merge - 1) / merge, 0);
    for (std::size_t i = 0; i < c.bins().size(); ++i)
        bins[i / merge] += c.bins()[i];
    const double bin_ns = c.binNs() * double(merge);
    const std::uint64_t peak = *std::max_element(bins.begin(), bins.end());
    SvgPlot plot("faults-over-time", 900, 220,
                 fmt::format("{}: events with errors per {}", inst, formatDuration(bin_ns)),
                 ta.axis(), {0, double(peak) * 1.1, "events with errors"});
    for (std::size_t i = 0; i < bins.size(); ++i) {
        if (!bins[i]) continue;
        const double xa = plot.x(ta.at(c.originNs() + bin_ns * double(i)));
        const double xb = plot.x(ta.at(c.originNs() + bin_ns * double(i + 1)));
        plot.body() += fmt::format(
            R"(<rect class="bar" x="{}" y="{}" width="{}" height="{}" fill="#c62828"><title>{}</title></rect>)",
            num(xa), num(plot.y(double(bins[i]))), num(std::max(xb - xa, 1.0)),
            num(plot.bottom() - plot.y(double(bins[i]))), bins[i]);
    }
    return plot.svg();
}

// A histogram where the values vary; a constant is said in words instead.
std::string histogramSvg(const std::string& title, const std::string& key,
                         const QuantileSketch& sk) {
    if (sk.count() < 1) return "";
    if (sk.min() == sk.max())
        return fmt::format(R"(<p class="constant">{}: {} in {}.</p>)", esc(title),
                           esc(formatFieldValue(key, sk.min())),
                           sk.count() == 1 ? std::string("the one event")
                                           : fmt::format("all {} events", sk.count()));
    const FieldAxis fa = fieldAxis(key, std::max(std::fabs(sk.min()), std::fabs(sk.max())));
    // Whole numbers over a short range get one bar per value, centred on it.
    const double span = sk.max() - sk.min();
    const bool per_value = sk.allIntegers() && span <= 40;
    const int bins = per_value ? int(span) + 1 : 24;
    const auto counts = sk.histogram(bins);
    const std::uint64_t peak = *std::max_element(counts.begin(), counts.end());
    const double lo = per_value ? sk.min() - 0.5 : sk.min(),
                 hi = per_value ? sk.max() + 0.5 : sk.max();
    SvgPlot plot("histogram", 440, 220, fmt::format("{} (n={})", title, sk.count()),
                 {lo / fa.scale, hi / fa.scale, fa.title}, {0, double(peak) * 1.1, "events"});
    if (per_value) {
        std::vector<double> ticks;
        const auto round = niceTicks(sk.min(), sk.max(), 8);
        const double step = std::max(1.0, round.size() > 1 ? round[1] - round[0] : 1.0);
        for (double v = std::ceil(sk.min() / step) * step; v <= sk.max(); v += step)
            ticks.push_back(v / fa.scale);  // on the axis, in its unit (ns shown as us)
        plot.xTicksAt(ticks);
    }
    const double bw = (hi - lo) / bins;
    for (int i = 0; i < bins; ++i) {
        if (!counts[std::size_t(i)]) continue;
        const double xa = plot.x((lo + bw * i) / fa.scale),
                     xb = plot.x((lo + bw * (i + 1)) / fa.scale);
        plot.body() += fmt::format(
            R"(<rect class="bar" x="{}" y="{}" width="{}" height="{}" fill="#2e7d32"><title>{}</title></rect>)",
            num(xa + 0.5), num(plot.y(double(counts[std::size_t(i)]))),
            num(std::max(xb - xa - 1, 1.0)),
            num(plot.bottom() - plot.y(double(counts[std::size_t(i)]))), counts[std::size_t(i)]);
    }
    return plot.svg();
}

std::string fieldText(const Field& f) {
    std::string v = std::holds_alternative<double>(f.value)
                        ? fmt::format("{:.7g}", std::get<double>(f.value))
                        : valueToJson(f.value);
    if (v.size() > 18) v = v.substr(0, 17) + "…";
    return f.key + "=" + v;
}

// Clock and data lines rebuilt from the decoded fields, with the field segments above them.
void appendRebuiltBits(std::string& body, double& y, const Event& e,
                       const std::vector<BitSegment>& layout, double L, double plot) {
    std::size_t nbits = 0;
    for (const auto& seg : layout)
        nbits += seg.bits.size();
    const double cw = plot / double(nbits);
    const bool biss = e.proto == "bissc";
    // Segment boxes
    double x = L;
    for (const auto& seg : layout) {
        const double w = cw * double(seg.bits.size());
        body += fmt::format(
            R"(<rect class="segment" x="{}" y="{}" width="{}" height="18" fill="{}" stroke="#555"/>)",
            num(x), y, num(w), seg.fault ? "#ffcdd2" : "#e3f2fd");
        if (w > 18)
            body += fmt::format(R"(<text x="{}" y="{}" text-anchor="middle"{}>{}</text>)",
                                num(x + w / 2), y + 13, seg.fault ? R"( fill="#b71c1c")" : "",
                                esc(seg.label));
        x += w;
    }
    y += 30;
    // Clock line: one falling-then-rising period per bit.
    std::string clk = fmt::format("M{},{}", L, y);
    for (std::size_t i = 0; i < nbits; ++i) {
        const double x0 = L + cw * double(i), xm = x0 + cw / 2, x1 = x0 + cw;
        clk += fmt::format(" L{0},{1} L{0},{2} L{3},{2} L{3},{1} L{4},{1}", num(x0), y, y + 20,
                           num(xm), num(x1));
    }
    body += fmt::format(R"(<text x="8" y="{}">{}</text>)", y + 14, biss ? "MA" : "CLK");
    body += fmt::format(
        R"(<path class="wave" d="{}" fill="none" stroke="#1b5e20" stroke-width="1.5"/>)", clk);
    y += 34;
    // Data line with the bit values.
    std::string data;
    std::size_t i = 0;
    for (const auto& seg : layout) {
        for (int b : seg.bits) {
            const double x0 = L + cw * double(i), x1 = x0 + cw;
            const double ly = b ? y : y + 20;
            data +=
                fmt::format("{}{},{} L{},{} ", data.empty() ? "M" : "L", num(x0), ly, num(x1), ly);
            if (cw >= 8)
                body +=
                    fmt::format(R"(<text x="{}" y="{}" text-anchor="middle"{}>{}</text>)",
                                num(x0 + cw / 2), y + 36, seg.fault ? R"( fill="#b71c1c")" : "", b);
            ++i;
        }
    }
    body += fmt::format(R"(<text x="8" y="{}">{}</text>)", y + 14, biss ? "SL" : "DATA");
    body += fmt::format(
        R"(<path class="wave" d="{}" fill="none" stroke="#0d47a1" stroke-width="1.5"/>)", data);
    y += 50;
    body += fmt::format(
        R"(<text x="{}" y="{}" fill="#777">bits rebuilt from the decoded fields, spread evenly over the frame</text>)",
        L, y);
    y += 16;
}

// Decoded fields as bus cells (hexagons), wrapped over rows.
void appendFieldCells(std::string& body, double& y, const Event& e, double L, double plot) {
    const double cell = 168;
    const int per_row = int(plot / cell);
    for (std::size_t i = 0; i < e.fields.size(); ++i) {
        if (i % std::size_t(per_row) == 0) {
            y += i ? 28 : 6;
            body += fmt::format(R"(<text x="8" y="{}">{}</text>)", y + 14, i ? "" : "fields");
        }
        const double x0 = L + cell * double(i % std::size_t(per_row)), x1 = x0 + cell - 4;
        const bool bad = fieldShowsFault(e, e.fields[i]);
        body += fmt::format(
            R"(<polygon class="field" points="{0},{1} {2},{3} {4},{3} {5},{1} {4},{6} {2},{6}" fill="{7}" stroke="{8}"/>)",
            num(x0), y + 10, num(x0 + 6), y, num(x1 - 6), num(x1), y + 20,
            bad ? "#ffcdd2" : "#fff8e1", bad ? "#b71c1c" : "#8d6e63");
        body += fmt::format(R"(<text x="{}" y="{}" text-anchor="middle"{}>{}</text>)",
                            num((x0 + x1) / 2), y + 14, bad ? R"( fill="#b71c1c")" : "",
                            esc(fieldText(e.fields[i])));
    }
    y += 40;
}

void appendTimeAxis(std::string& body, double y, double L, double W, double R, double start_ns,
                    double end_ns) {
    const double plot = W - L - R;
    body +=
        fmt::format(R"(<line x1="{0}" y1="{1}" x2="{2}" y2="{1}" stroke="#888"/>)", L, y, W - R);
    for (int k = 0; k <= 4; ++k) {
        const double tx = L + plot * k / 4;
        body += fmt::format(R"(<line x1="{0}" y1="{1}" x2="{0}" y2="{2}" stroke="#888"/>)", num(tx),
                            y - 4, y + 4);
        const double t = start_ns + (end_ns - start_ns) * k / 4;
        body += fmt::format(R"(<text x="{}" y="{}" text-anchor="{}">{}</text>)", num(tx), y + 16,
                            k == 0   ? "start"
                            : k == 4 ? "end"
                                     : "middle",
                            esc(formatDuration(t)));
    }
}

// The first faulty event drawn like a logic analyser screen: reconstructed lines with
// bit values, field segments above them, decoded fields as bus cells, faults in red.
std::string timingDiagramSvg(const Event& e, const Timebase& tb, bool rebuild_bits) {
    auto layout = rebuild_bits ? frameLayout(e) : std::vector<BitSegment>{};
    std::size_t total_bits = 0;
    for (const auto& seg : layout)
        total_bits += seg.bits.size();
    if (total_bits > 400) layout.clear();  // too many cells to read: fields only
    const double W = 960, L = 110, R = 16;
    const double plot = W - L - R;
    const double start_ns = tb.toNsF(double(e.start)), end_ns = tb.toNsF(double(e.end));
    std::string body;
    double y = 34;

    if (!layout.empty()) appendRebuiltBits(body, y, e, layout, L, plot);
    appendFieldCells(body, y, e, L, plot);
    // Errors
    std::string errs;
    for (const auto& err : e.errors)
        errs += (errs.empty() ? "" : ", ") + err;
    body += fmt::format(R"(<text class="errors" x="8" y="{}" fill="#b71c1c">errors: {}</text>)", y,
                        esc(errs.empty() ? "none" : errs));
    y += 22;
    appendTimeAxis(body, y, L, W, R, start_ns, end_ns);
    y += 24;
    std::string head = fmt::format(
        R"(<svg class="timing" xmlns="http://www.w3.org/2000/svg" width="{0}" height="{1}" viewBox="0 0 {0} {1}">)",
        W, num(y));
    head += fmt::format(R"(<text x="8" y="16">{} {} at {} ({} long)</text>)",
                        esc(e.instance.empty() ? e.proto : e.instance), esc(e.type),
                        esc(formatDuration(start_ns)), esc(formatDuration(end_ns - start_ns)));
    return head + body + "</svg>\n";
}

std::string captureFactsHtml(const CaptureFacts& f) {
    std::string h;
    const Timebase& tb = f.timebase;
    h += "<h2>Capture</h2><table>\n";
    auto row = [&](const std::string& k, const std::string& v) {
        h += fmt::format("<tr><th>{}</th><td>{}</td></tr>\n", esc(k), esc(v));
    };
    row("file", f.file.empty() ? "-" : f.file);
    row("format", f.format.empty() ? "-" : f.format);
    row("duration", formatDuration(tb.toNsF(double(f.end - f.start))));
    row("timebase", fmt::format("{} per tick ({} sample rate)", formatDuration(tb.nsPerTick()),
                                formatFrequency(tb.sampleRateHz())));
    row("edges", fmt::format("{} on the mapped lines, {} read", f.edges, formatBytes(f.bytes)));
    for (const auto& b : f.bindings)
        row("signal", fmt::format("{}.{} = {}", b.instance, b.role, b.signal));
    h += "</table>\n";
    return h;
}

// Event counts, faults, errors and flags per event type of one bus.
std::string groupTableHtml(const std::vector<const GroupStats*>& groups) {
    std::string h;
    h += "<table><tr><th>type</th><th>events</th><th>with faults</th><th>errors by "
         "kind</th><th>flags</th></tr>\n";
    for (const GroupStats* g : groups) {
        std::string errs, flags;
        for (const auto& [k, n] : g->errors)
            errs += fmt::format("{}{} {}", errs.empty() ? "" : ", ", k, n);
        for (const auto& [k, c] : g->flags) {
            if (k == "nE" || k == "nW")
                flags += fmt::format("{}{} active {}", flags.empty() ? "" : ", ", k, c.false_count);
            else
                flags += fmt::format("{}{} true {} / false {}", flags.empty() ? "" : ", ", k,
                                     c.true_count, c.false_count);
        }
        h += fmt::format(
            "<tr><td>{}</td><td class=\"n\">{}</td><td "
            "class=\"n{}\">{}</td><td>{}</td><td>{}</td></tr>\n",
            esc(g->type), g->count, g->faulty ? " fault" : "", g->faulty, esc(errs), esc(flags));
    }
    h += "</table>\n";
    return h;
}

std::string registersHtml(const CaptureStats& stats, const std::string& inst) {
    std::string h;
    if (const auto* regs = stats.registers(inst); regs && !regs->empty()) {
        h += "<table><tr><th>register</th><th>reads</th><th>writes</th><th>last "
             "data</th></tr>\n";
        for (const auto& [a, r] : *regs)
            h += fmt::format(
                "<tr><td>0x{:02X}</td><td class=\"n\">{}</td><td "
                "class=\"n\">{}</td><td>0x{:02X}{}</td></tr>\n",
                a, r.reads, r.writes, r.last_data, r.crc_failed ? " (CRC failed)" : "");
        h += "</table>\n";
    }
    return h;
}

// Quantiles and histograms of every timed field per event type.
std::string timingTablesHtml(const std::vector<const GroupStats*>& groups) {
    std::string h;
    for (const GroupStats* g : groups) {
        const auto rows = g->timingRows();
        if (rows.empty()) continue;
        h += fmt::format(
            "<h3>{} "
            "timing</h3><table><tr><th>field</th><th>n</th><th>min</th><th>median</th><th>p99</"
            "th><th>max</th></tr>\n",
            esc(g->type));
        for (const auto& [k, s] : rows)
            h += fmt::format(
                "<tr><td>{}</td><td class=\"n\">{}</td><td class=\"n\">{}</td><td "
                "class=\"n\">{}</td><td class=\"n\">{}</td><td class=\"n\">{}</td></tr>\n",
                esc(k == "pause_ns" ? "pause between" : k), s->count(),
                esc(formatFieldValue(k, s->min())), esc(formatFieldValue(k, s->median())),
                esc(formatFieldValue(k, s->quantile(0.99))), esc(formatFieldValue(k, s->max())));
        h += "</table>\n<div>";
        for (const auto& [k, s] : rows)
            h += histogramSvg(fmt::format("{} {}", g->type, k == "pause_ns" ? "pause between" : k),
                              k, *s);
        h += "</div>\n";
    }
    return h;
}

std::string positionHtml(const CaptureStats& stats, const std::string& inst, const Timebase& tb) {
    std::string h;
    if (const auto* p = stats.position(inst)) {
        h += fmt::format("<p>Position: min {:.0f}, max {:.0f}, range {:.0f} over {} values", p->min,
                         p->max, p->max - p->min, p->count);
        if (p->count > 1 && p->max_jump > 0)
            h += fmt::format("; largest jump {:.0f} at {}", p->max_jump,
                             esc(formatDuration(tb.toNsF(double(p->max_jump_at)))));
        else if (p->count > 1)
            h += "; it never changed";
        h += ".</p>\n" + positionSvgs(stats, inst, *p);
    }
    return h;
}

std::string busSectionHtml(const CaptureStats& stats, const std::string& inst, const Timebase& tb) {
    std::string h;
    h += fmt::format("<h2>Bus {}</h2>\n", esc(inst));
    const auto groups = stats.groupsOf(inst);
    if (groups.empty()) return h + "<p>No events decoded.</p>\n";
    h += groupTableHtml(groups);
    h += registersHtml(stats, inst);
    h += timingTablesHtml(groups);
    h += positionHtml(stats, inst, tb);
    if (const auto* c = stats.faultsOverTime(inst)) h += faultsOverTimeSvg(stats, inst, *c);
    return h;
}

std::string waveformsHtml(const CaptureStats& stats, const CaptureFacts& f) {
    std::string h;
    const Timebase& tb = f.timebase;
    if (!stats.waveforms().empty()) {
        h += "<h2>Captured waveforms</h2>\n<p>The first faulty events of each bus as captured, "
             "with a clean one of each event type for comparison: the decoder's sample points "
             "(orange), the bits read there, the decoded fields above them; for an analog line "
             "(a scope capture) the voltage as sampled below its levels, with the threshold "
             "(dashed) and the hysteresis band the edges were found with.</p>\n";
        for (const FrameWave& w : stats.waveforms()) {
            auto opts = f.options.find(w.event.instance);
            h += waveformSvg(
                w, tb,
                opts == f.options.end() ? std::map<std::string, std::string>{} : opts->second);
        }
    }
    return h;
}

std::string faultsHtml(const CaptureStats& stats, const Timebase& tb) {
    std::string h;
    h += "<h2>Faults</h2>\n";
    if (stats.firstFaults().empty()) {
        h += "<p>None.</p>\n";
    } else {
        h += fmt::format("<p>{} event{} with errors{}.</p><pre>", stats.totalFaults(),
                         stats.totalFaults() == 1 ? "" : "s",
                         stats.totalFaults() > stats.firstFaults().size()
                             ? fmt::format("; the first {}", stats.firstFaults().size())
                             : "");
        for (const auto& fr : stats.firstFaults())
            h += esc(fr.text) + "\n";
        h += "</pre>\n";
        if (const auto& e = stats.firstFaultyEvent()) {
            h += "<h3>First faulty event</h3>\n";
            h += timingDiagramSvg(*e, tb, stats.waveforms().empty());
        }
    }
    return h;
}

}  // namespace

std::string htmlEscape(const std::string& s) {
    return xmlEscape(s);
}

std::string renderHtmlReport(const CaptureStats& stats) {
    const CaptureFacts& f = stats.facts();
    const Timebase& tb = f.timebase;
    std::string h;
    h += "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">";
    h += fmt::format("<title>busdecode report: {}</title><style>{}</style></head><body>\n",
                     esc(f.file.empty() ? "capture" : f.file), kStyle);
    h += fmt::format("<h1>busdecode report: {}</h1>\n", esc(f.file.empty() ? "capture" : f.file));

    h += captureFactsHtml(f);

    for (const auto& inst : stats.instances())
        h += busSectionHtml(stats, inst, tb);

    h += waveformsHtml(stats, f);
    h += stats.signalSection().html();
    h += faultsHtml(stats, tb);
    h += "<h2>Text report</h2>\n<pre>" + esc(renderTextReport(stats)) + "</pre>\n";
    h += "</body></html>\n";
    return h;
}

}  // namespace busdecode
