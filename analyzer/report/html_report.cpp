#include "html_report.h"

#include "sinks/xml_escape.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "frame_layout.h"
#include "report_format.h"
#include "sinks/event_format.h"
#include "text_report.h"

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

// Position over time: one vertical stroke per trace point (its min..max), joined.
std::string positionSvg(const CaptureStats& stats, const std::string& inst,
                        const PositionStats& p) {
    const auto& pts = p.trace.points();
    if (pts.empty()) return "";
    const Timebase& tb = stats.facts().timebase;
    const double W = 900, H = 240, L = 90, R = 10, T = 20, B = 30;
    double t0 = tb.toNsF(double(stats.facts().start)), t1 = tb.toNsF(double(stats.facts().end));
    if (!(t1 > t0)) {
        t0 = pts.front().t_ns;
        t1 = std::max(pts.back().t_ns, t0 + 1);
    }
    double lo = p.min, hi = p.max;
    if (hi <= lo) {
        lo -= 1;
        hi += 1;
    }
    auto x = [&](double t) { return L + (t - t0) / (t1 - t0) * (W - L - R); };
    auto y = [&](double v) { return T + (hi - v) / (hi - lo) * (H - T - B); };
    std::string path;
    for (const auto& q : pts) {
        path += fmt::format("{}{},{} L{},{} ", path.empty() ? "M" : "L", num(x(q.t_ns)),
                            num(y(q.lo)), num(x(q.t_ns)), num(y(q.hi)));
    }
    std::string s = fmt::format(
        R"(<svg class="position" xmlns="http://www.w3.org/2000/svg" width="{0}" height="{1}" viewBox="0 0 {0} {1}">)",
        W, H);
    s += fmt::format(R"(<text x="{}" y="14">{} position over time ({} points)</text>)", L,
                     esc(inst), pts.size());
    s += fmt::format(R"(<line x1="{0}" y1="{1}" x2="{0}" y2="{2}" stroke="#888"/>)", L, T, H - B);
    s += fmt::format(R"(<line x1="{0}" y1="{1}" x2="{2}" y2="{1}" stroke="#888"/>)", L, H - B,
                     W - R);
    s += fmt::format(R"(<text x="4" y="{}">{:.0f}</text><text x="4" y="{}">{:.0f}</text>)", T + 8,
                     hi, H - B, lo);
    s += fmt::format(R"(<text x="{}" y="{}">{}</text>)", L, H - 10, esc(formatDuration(t0)));
    s += fmt::format(R"(<text x="{}" y="{}" text-anchor="end">{}</text>)", W - R, H - 10,
                     esc(formatDuration(t1)));
    s += fmt::format(R"(<path d="{}" fill="none" stroke="#1565c0" stroke-width="1.2"/>)", path);
    if (p.count > 1 && p.max_jump > 0) {
        const double jx = x(tb.toNsF(double(p.max_jump_at)));
        s += fmt::format(
            R"(<line x1="{0}" y1="{1}" x2="{0}" y2="{2}" stroke="#c62828" stroke-dasharray="4 3"/>)",
            num(jx), T, H - B);
        s += fmt::format(R"(<text x="{}" y="{}" fill="#c62828">largest jump {:.0f}</text>)",
                         num(jx + 4), T + 12, p.max_jump);
    }
    return s + "</svg>\n";
}

std::string histogramSvg(const std::string& title, const std::string& key,
                         const QuantileSketch& sk) {
    if (sk.count() < 1) return "";
    const int bins = sk.min() == sk.max() ? 1 : 24;
    const auto counts = sk.histogram(bins);
    const std::uint64_t peak = *std::max_element(counts.begin(), counts.end());
    const double W = 440, H = 200, L = 50, R = 10, T = 22, B = 30;
    // A constant value gets one narrow bar in the middle rather than a full-width block.
    const double bw = bins == 1 ? 40.0 : (W - L - R) / bins;
    const double x0 = bins == 1 ? L + (W - L - R - bw) / 2 : L;
    std::string s = fmt::format(
        R"(<svg class="histogram" xmlns="http://www.w3.org/2000/svg" width="{0}" height="{1}" viewBox="0 0 {0} {1}">)",
        W, H);
    s += fmt::format(R"(<text x="{}" y="14">{} (n={})</text>)", L, esc(title), sk.count());
    for (int i = 0; i < bins; ++i) {
        const double h = peak ? double(counts[i]) / double(peak) * (H - T - B) : 0;
        s += fmt::format(
            R"(<rect x="{}" y="{}" width="{}" height="{}" fill="#2e7d32"><title>{}</title></rect>)",
            num(x0 + i * bw + 1), num(H - B - h), num(std::max(bw - 2, 1.0)), num(h), counts[i]);
    }
    s += fmt::format(R"(<line x1="{0}" y1="{1}" x2="{2}" y2="{1}" stroke="#888"/>)", L, H - B,
                     W - R);
    s += fmt::format(R"(<text x="4" y="{}">{}</text>)", T + 8, peak);
    s += fmt::format(R"(<text x="{}" y="{}">{}</text>)", L, H - 10,
                     esc(formatFieldValue(key, sk.min())));
    s += fmt::format(R"(<text x="{}" y="{}" text-anchor="end">{}</text>)", W - R, H - 10,
                     esc(formatFieldValue(key, sk.max())));
    return s + "</svg>\n";
}

std::string fieldText(const Field& f) {
    std::string v = std::holds_alternative<double>(f.value)
                        ? fmt::format("{:.7g}", std::get<double>(f.value))
                        : valueToJson(f.value);
    if (v.size() > 18) v = v.substr(0, 17) + "…";
    return f.key + "=" + v;
}

// The first faulty event drawn like a logic analyser screen: reconstructed lines with
// bit values, field segments above them, decoded fields as bus cells, faults in red.
std::string timingDiagramSvg(const Event& e, const Timebase& tb) {
    auto layout = frameLayout(e);
    std::size_t total_bits = 0;
    for (const auto& seg : layout)
        total_bits += seg.bits.size();
    if (total_bits > 400) layout.clear();  // too many cells to read: fields only
    const double W = 960, L = 110, R = 16;
    const double plot = W - L - R;
    const double start_ns = tb.toNsF(double(e.start)), end_ns = tb.toNsF(double(e.end));
    std::string body;
    double y = 34;

    if (!layout.empty()) {
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
                data += fmt::format("{}{},{} L{},{} ", data.empty() ? "M" : "L", num(x0), ly,
                                    num(x1), ly);
                if (cw >= 8)
                    body += fmt::format(R"(<text x="{}" y="{}" text-anchor="middle"{}>{}</text>)",
                                        num(x0 + cw / 2), y + 36,
                                        seg.fault ? R"( fill="#b71c1c")" : "", b);
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

    // Errors
    std::string errs;
    for (const auto& err : e.errors)
        errs += (errs.empty() ? "" : ", ") + err;
    body += fmt::format(R"(<text class="errors" x="8" y="{}" fill="#b71c1c">errors: {}</text>)", y,
                        esc(errs.empty() ? "none" : errs));
    y += 22;
    // Time axis
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
    y += 24;
    std::string head = fmt::format(
        R"(<svg class="timing" xmlns="http://www.w3.org/2000/svg" width="{0}" height="{1}" viewBox="0 0 {0} {1}">)",
        W, num(y));
    head += fmt::format(R"(<text x="8" y="16">{} {} at {} ({} long)</text>)",
                        esc(e.instance.empty() ? e.proto : e.instance), esc(e.type),
                        esc(formatDuration(start_ns)), esc(formatDuration(end_ns - start_ns)));
    return head + body + "</svg>\n";
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

    // Capture facts
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

    for (const auto& inst : stats.instances()) {
        h += fmt::format("<h2>Bus {}</h2>\n", esc(inst));
        const auto groups = stats.groupsOf(inst);
        if (groups.empty()) {
            h += "<p>No events decoded.</p>\n";
            continue;
        }
        h += "<table><tr><th>type</th><th>events</th><th>with faults</th><th>errors by "
             "kind</th><th>flags</th></tr>\n";
        for (const GroupStats* g : groups) {
            std::string errs, flags;
            for (const auto& [k, n] : g->errors)
                errs += fmt::format("{}{} {}", errs.empty() ? "" : ", ", k, n);
            for (const auto& [k, c] : g->flags) {
                if (k == "nE" || k == "nW")
                    flags +=
                        fmt::format("{}{} active {}", flags.empty() ? "" : ", ", k, c.false_count);
                else
                    flags += fmt::format("{}{} true {} / false {}", flags.empty() ? "" : ", ", k,
                                         c.true_count, c.false_count);
            }
            h += fmt::format(
                "<tr><td>{}</td><td class=\"n\">{}</td><td "
                "class=\"n{}\">{}</td><td>{}</td><td>{}</td></tr>\n",
                esc(g->type), g->count, g->faulty ? " fault" : "", g->faulty, esc(errs),
                esc(flags));
        }
        h += "</table>\n";
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
        for (const GroupStats* g : groups) {
            std::vector<std::pair<std::string, const QuantileSketch*>> rows;
            for (const auto& [k, s] : g->timing)
                rows.emplace_back(k, &s);
            if (!g->pause_ns.empty()) rows.emplace_back("pause_ns", &g->pause_ns);
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
                    esc(formatFieldValue(k, s->quantile(0.99))),
                    esc(formatFieldValue(k, s->max())));
            h += "</table>\n<div>";
            for (const auto& [k, s] : rows)
                h += histogramSvg(
                    fmt::format("{} {}", g->type, k == "pause_ns" ? "pause between" : k), k, *s);
            h += "</div>\n";
        }
        if (const auto* p = stats.position(inst)) {
            h += fmt::format("<p>Position: min {:.0f}, max {:.0f}, range {:.0f} over {} values",
                             p->min, p->max, p->max - p->min, p->count);
            if (p->count > 1)
                h += fmt::format("; largest jump {:.0f} at {}", p->max_jump,
                                 esc(formatDuration(tb.toNsF(double(p->max_jump_at)))));
            h += ".</p>\n" + positionSvg(stats, inst, *p);
        }
    }

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
            h += timingDiagramSvg(*e, tb);
        }
    }
    h += "<h2>Text report</h2>\n<pre>" + esc(renderTextReport(stats)) + "</pre>\n";
    h += "</body></html>\n";
    return h;
}

}  // namespace busdecode
