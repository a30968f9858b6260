#include "scope_csv_writer.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include <fmt/format.h>

#include "core/atomic_file.h"

namespace busdecode {

namespace {

// One line's voltage over time, from its edges: a linear ramp centred on each edge, then
// a damped ringing.
class LineShape {
public:
    LineShape(std::vector<std::pair<double, int>> edges, int initial, const AnalogStyle& s)
        : edges_(std::move(edges)), level_(initial), s_(s) {}
    // Normalised level (0 low, 1 high, overshoot beyond) at `ns`; calls in time order.
    double at(double ns) {
        while (next_ < edges_.size() && edges_[next_].first - s_.rise_ns / 2 <= ns)
            last_ = next_++;
        if (last_ == kNone) return level_;
        const auto [te, to] = edges_[last_];
        const int from = last_ == 0 ? level_ : edges_[last_ - 1].second;
        const double x = ns - (te - s_.rise_ns / 2);
        const double dir = to - from;
        if (s_.rise_ns > 0 && x < s_.rise_ns) return from + dir * x / s_.rise_ns;
        const double y = x - s_.rise_ns;
        const double ring =
            s_.ringing * std::exp(-y / s_.ring_ns) * std::sin(2 * M_PI * y / s_.ring_ns + M_PI / 2);
        return to + dir * ring;
    }

private:
    static constexpr std::size_t kNone = ~std::size_t(0);
    std::vector<std::pair<double, int>> edges_;  // (ns, level after)
    int level_;
    const AnalogStyle& s_;
    std::size_t next_ = 0, last_ = kNone;
};

struct Column {
    std::string name;
    std::size_t line;
    bool negative;
};

std::string header(ScopeDialect d, const std::vector<Column>& cols, double start_s, double dt_s,
                   std::size_t rows) {
    std::string names, units, pico_names, pico_units;
    for (const auto& c : cols) {
        names += "," + c.name;
        units += ",Volt";
        pico_names += ";Channel " + c.name;
        pico_units += ";(V)";
    }
    switch (d) {
        case ScopeDialect::Rigol:
            return fmt::format("X{},Start,Increment,\r\nSequence{},{:e},{:e}\r\n", names, units,
                               start_s, dt_s);
        case ScopeDialect::Keysight:
            return fmt::format("x-axis{}\nsecond{}\n", names, units);
        case ScopeDialect::Tektronix:
            return fmt::format(
                "Model,MDO4104C\nFirmware Version,1.10\n\nWaveform Type,ANALOG,\nPoint Format,Y,\n"
                "Horizontal Units,s,\nSample Interval,{:g},\nRecord Length,{},\n,,\nLabel,,\n"
                "TIME{}\n",
                dt_s, rows, names);
        case ScopeDialect::Siglent:
            return fmt::format(
                "Record Length,Analog:{}\nSample Interval,CH1:{:.13f}\nModel Number,SDS1202X-E,,,\n"
                "Source{}\nSecond{}\n",
                rows, dt_s, names, units);
        case ScopeDialect::PicoScope:
            return fmt::format("Time{}\n(us){}\n\n", pico_names, pico_units);
        case ScopeDialect::LeCroy:
            return fmt::format(
                "LECROYWR204M,51184,Waveform\nSegments,1,SegmentSize,{}\n"
                "Segment,TrigTime,TimeSinceSegment1\n#1,22-Jan-2015 11:35:11,0   \nTime{}\n",
                rows, names);
    }
    return "";
}

std::string timeText(ScopeDialect d, std::size_t k, double t_s) {
    switch (d) {
        case ScopeDialect::Rigol:
            return fmt::format("{}", k);
        case ScopeDialect::Keysight:
            return fmt::format("{:+.9E}", t_s);
        case ScopeDialect::Siglent:
            return fmt::format(" {:.11f}", t_s);
        case ScopeDialect::PicoScope: {
            std::string s = fmt::format("{:.6f}", t_s * 1e6);
            std::replace(s.begin(), s.end(), '.', ',');
            return s;
        }
        default:
            return fmt::format("{:.6e}", t_s);
    }
}

}  // namespace

const char* scopeDialectName(ScopeDialect d) {
    switch (d) {
        case ScopeDialect::Rigol:
            return "rigol";
        case ScopeDialect::Keysight:
            return "keysight";
        case ScopeDialect::Tektronix:
            return "tektronix";
        case ScopeDialect::Siglent:
            return "siglent";
        case ScopeDialect::PicoScope:
            return "picoscope";
        case ScopeDialect::LeCroy:
            return "lecroy";
    }
    return "";
}

void writeScopeCsv(const Waveform& w, const std::string& path, ScopeDialect d,
                   const AnalogStyle& s) {
    std::vector<std::vector<std::pair<double, int>>> edges(w.names.size());
    for (const Edge& e : w.edges)
        edges[e.line].push_back({double(w.timebase.toNs(e.t)), int(e.level)});
    std::vector<LineShape> shapes;
    std::vector<Column> cols;
    for (std::size_t i = 0; i < w.names.size(); ++i) {
        shapes.emplace_back(edges[i], w.initial.size() > i ? w.initial[i] : 0, s);
        cols.push_back({s.differential ? w.names[i] + "+" : w.names[i], i, false});
        if (s.differential) cols.push_back({w.names[i] + "-", i, true});
    }
    const double t0 = double(w.timebase.toNs(w.start)), t1 = double(w.timebase.toNs(w.end));
    const auto rows = std::size_t((t1 - t0) / s.sample_ns) + 1;
    const double swing = s.high_v - s.low_v;
    std::mt19937_64 rng(s.seed);
    std::normal_distribution<double> noise(
        0, s.snr_db > 0 ? swing / 2 / std::pow(10, s.snr_db / 20) : 1);
    AtomicFile out(path);
    out.put(header(d, cols, t0 * 1e-9, s.sample_ns * 1e-9, rows));
    const char sep = d == ScopeDialect::PicoScope ? ';' : ',';
    std::vector<double> level(w.names.size());
    std::string row;
    for (std::size_t k = 0; k < rows; ++k) {
        const double ns = t0 + double(k) * s.sample_ns;
        for (std::size_t i = 0; i < shapes.size(); ++i)
            level[i] = shapes[i].at(ns);
        row = timeText(d, k, ns * 1e-9);
        for (const auto& c : cols) {
            double x = c.negative ? 1 - level[c.line] : level[c.line];
            if (c.negative && int(c.line) == s.open_line && ns >= s.open_after_ns) x = 0.5;
            double v = s.low_v + swing * x + s.offset_v + (s.snr_db > 0 ? noise(rng) : 0);
            std::string text = fmt::format("{:.4e}", v);
            if (sep == ';') std::replace(text.begin(), text.end(), '.', ',');
            row += sep;
            row += text;
        }
        row += d == ScopeDialect::Rigol ? ",\r\n" : "\n";
        out.put(row);
    }
    out.commit();
}

}  // namespace busdecode
