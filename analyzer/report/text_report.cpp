#include "text_report.h"

#include <fmt/format.h>

#include "report_format.h"
#include "sinks/event_format.h"

namespace busdecode {

namespace {

constexpr int kHistogramBins = 8;
constexpr int kHistogramWidth = 30;

void line(std::string& out, const std::string& s) {
    out += s;
    out += '\n';
}

void captureSection(std::string& out, const CaptureStats& stats) {
    const CaptureFacts& f = stats.facts();
    const Timebase& tb = f.timebase;
    line(out, "Capture");
    line(out, fmt::format("  file        {}", f.file.empty() ? "-" : f.file));
    line(out, fmt::format("  format      {}", f.format.empty() ? "-" : f.format));
    const double dur = tb.toNsF(double(f.end - f.start));
    line(out, fmt::format("  duration    {}  ({} .. {})", formatDuration(dur),
                          formatDuration(tb.toNsF(double(f.start))),
                          formatDuration(tb.toNsF(double(f.end)))));
    line(out, fmt::format("  timebase    {} per tick ({} sample rate)",
                          formatDuration(tb.nsPerTick()), formatFrequency(tb.sampleRateHz())));
    line(out, fmt::format("  edges       {} on the mapped lines, {} read", f.edges,
                          formatBytes(f.bytes)));
    if (f.bindings.empty()) {
        line(out, "  signals     -");
    } else {
        for (std::size_t i = 0; i < f.bindings.size(); ++i) {
            const auto& b = f.bindings[i];
            line(out, fmt::format("  {:<11} {}.{} = {}", i ? "" : "signals", b.instance, b.role,
                                  b.signal));
        }
    }
}

void busSection(std::string& out, const CaptureStats& stats, const std::string& inst) {
    const Timebase& tb = stats.facts().timebase;
    const auto groups = stats.groupsOf(inst);
    line(out, "");
    line(out, fmt::format("Bus {}", inst));
    if (groups.empty()) {
        line(out, "  no events decoded");
        return;
    }
    for (const GroupStats* g : groups) {
        std::string errs;
        for (const auto& [k, n] : g->errors)
            errs += fmt::format("{}{} {}", errs.empty() ? "" : ", ", k, n);
        line(out, fmt::format("  {:<12} {:>8} events, {} with faults{}", g->type, g->count,
                              g->faulty, errs.empty() ? "" : " (" + errs + ")"));
        for (const auto& [k, c] : g->flags) {
            if (k == "nE" || k == "nW")
                line(out, fmt::format("    {:<18} active {} of {}", k, c.false_count,
                                      c.false_count + c.true_count));
            else
                line(out,
                     fmt::format("    {:<18} true {}, false {}", k, c.true_count, c.false_count));
        }
    }
    if (const auto* regs = stats.registers(inst); regs && !regs->empty()) {
        line(out, "  registers   address  reads  writes  last data");
        for (const auto& [addr, r] : *regs)
            line(out, fmt::format("              0x{:02X}  {:>6}  {:>6}  0x{:02X}{}", addr, r.reads,
                                  r.writes, r.last_data, r.crc_failed ? "  (CRC failed)" : ""));
    }
    if (const auto* p = stats.position(inst)) {
        line(out, fmt::format("  position    min {:.0f}  max {:.0f}  range {:.0f}  ({} values)",
                              p->min, p->max, p->max - p->min, p->count));
        if (p->count > 1 && p->max_jump > 0)
            line(out, fmt::format("              largest jump {:.0f} at {}", p->max_jump,
                                  formatDuration(tb.toNsF(double(p->max_jump_at)))));
        else if (p->count > 1)
            line(out, "              it never changed");
    }
    for (const GroupStats* g : groups) {
        const auto rows = g->timingRows();
        if (rows.empty()) continue;
        line(out, "");
        // The label column is as wide as the rows' (4 + 28), so the headings sit over them.
        line(out, fmt::format("  {:<30} {:>8} {:>13} {:>13} {:>13} {:>13}", g->type + " timing",
                              "n", "min", "median", "p99", "max"));
        for (const auto& [k, s] : rows) {
            const std::string label = k == "pause_ns" ? "pause between" : k;
            line(out, fmt::format("    {:<28} {:>8} {:>13} {:>13} {:>13} {:>13}", label, s->count(),
                                  formatFieldValue(k, s->min()), formatFieldValue(k, s->median()),
                                  formatFieldValue(k, s->quantile(0.99)),
                                  formatFieldValue(k, s->max())));
        }
        for (const auto& [k, s] : rows) {
            if (s->count() < 2 || s->min() == s->max()) continue;  // nothing to draw
            line(out, fmt::format("    {} {}:", g->type, k == "pause_ns" ? "pause between" : k));
            for (const auto& r : textHistogram(k, *s, kHistogramBins, kHistogramWidth))
                line(out, "      " + r);
        }
    }
}

void faultSection(std::string& out, const CaptureStats& stats) {
    line(out, "");
    const auto& faults = stats.firstFaults();
    if (faults.empty()) {
        line(out, "Faults: none");
        return;
    }
    const std::uint64_t n = stats.totalFaults();
    line(out,
         fmt::format("Faults: {} event{} with errors{}", n, n == 1 ? "" : "s",
                     n > faults.size() ? fmt::format(" (the first {} below)", faults.size()) : ""));
    for (const auto& f : faults)
        line(out, "  " + f.text);
}

}  // namespace

std::string renderTextReport(const CaptureStats& stats) {
    std::string out;
    line(out, "busdecode report");
    line(out, "================");
    line(out, "");
    captureSection(out, stats);
    for (const auto& inst : stats.instances())
        busSection(out, stats, inst);
    out += stats.signalSection().text();
    faultSection(out, stats);
    return out;
}

}  // namespace busdecode
