// Capture writers: a Waveform as VCD (sigrok's dialect) or CSV (sigrok dense, Saleae
// Logic 2, plain; sigrok sessions are in sr_writer.cpp), written to a temporary file beside the
// target and renamed into place, so a reader never sees half a file.
#include "capture_writer.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <unistd.h>

#include "core/atomic_file.h"
#include "core/options.h"

namespace busdecode {

namespace {

// VCD identifier codes: `!`..`~`, then two characters, and so on.
std::string vcdId(std::size_t i) {
    std::string id;
    do {
        id += char(33 + i % 94);
        i /= 94;
    } while (i-- > 0);
    return id;
}

std::string safeName(const std::string& n) {
    std::string out = n;
    for (auto& c : out)
        if (static_cast<unsigned char>(c) <= ' ' || c == '$') c = '_';
    return out.empty() ? "_" : out;
}

__int128 pow10(int e) {
    __int128 v = 1;
    while (e-- > 0)
        v *= 10;
    return v;
}

// n / 10^e seconds per tick with n in {1, 10, 100}, if the timebase is such a value.
bool vcdTimescale(const Timebase& tb, std::string& text) {
    static const std::pair<int, const char*> units[] = {{0, "s"},  {3, "ms"},  {6, "us"},
                                                        {9, "ns"}, {12, "ps"}, {15, "fs"}};
    for (const auto& [e, u] : units)
        for (int n : {1, 10, 100})
            if ((__int128)tb.num * pow10(e) == (__int128)n * tb.den) {
                text = fmt::format("{} {}", n, u);
                return true;
            }
    return false;
}

// t ticks in units of 10^-digits s, rounded to nearest.
__int128 scaled(Tick t, const Timebase& tb, int digits) {
    __int128 v = (__int128)t * tb.num * pow10(digits);
    __int128 q = v / tb.den, r = v % tb.den;
    if (2 * (r < 0 ? -r : r) >= tb.den) q += v < 0 ? -1 : 1;
    return q;
}

std::string decimalSeconds(__int128 v, int digits) {
    const bool neg = v < 0;
    if (neg) v = -v;
    const __int128 p = pow10(digits);
    const auto ip = (long long)(v / p);
    const auto fp = (long long)(v % p);
    if (digits == 0) return fmt::format("{}{}", neg ? "-" : "", ip);
    return fmt::format("{}{}.{:0{}}", neg ? "-" : "", ip, fp, digits);
}

}  // namespace

std::string sampleRateText(std::int64_t hz) {
    if (hz % 1'000'000'000 == 0) return fmt::format("{} GHz", hz / 1'000'000'000);
    if (hz % 1'000'000 == 0) return fmt::format("{} MHz", hz / 1'000'000);
    if (hz % 1000 == 0) return fmt::format("{} kHz", hz / 1000);
    return fmt::format("{} Hz", hz);
}

void writeVcd(const Waveform& w, const std::string& path) {
    std::string ts;
    const bool exact = vcdTimescale(w.timebase, ts);
    if (!exact) ts = "1 ps";
    auto when = [&](Tick t) -> long long {
        return exact ? t : (long long)scaled(t, w.timebase, 12);
    };

    AtomicFile out(path);
    std::vector<std::string> ids;
    out.put("$version busdecode $end\n");
    out.put(fmt::format("$comment\n  {} lines, timebase {}/{} s\n$end\n", w.names.size(),
                        w.timebase.num, w.timebase.den));
    out.put(fmt::format("$timescale {} $end\n$scope module busdecode $end\n", ts));
    for (std::size_t i = 0; i < w.names.size(); ++i) {
        ids.push_back(vcdId(i));
        out.put(fmt::format("$var wire 1 {} {} $end\n", ids[i], safeName(w.names[i])));
    }
    out.put("$upscope $end\n$enddefinitions $end\n");
    std::string line = fmt::format("#{}", when(w.start));
    for (std::size_t i = 0; i < w.names.size(); ++i)
        line += fmt::format(" {}{}", w.initial.size() > i && w.initial[i] ? 1 : 0, ids[i]);
    out.put(line + "\n");
    // sigrok's dialect: all changes of one timestamp on its line
    long long last = when(w.start);
    for (std::size_t k = 0; k < w.edges.size();) {
        const long long t = std::max(when(w.edges[k].t), last);
        line = fmt::format("#{}", t);
        for (; k < w.edges.size() && std::max(when(w.edges[k].t), last) == t; ++k)
            line += fmt::format(" {}{}", w.edges[k].level ? 1 : 0, ids[w.edges[k].line]);
        out.put(line + "\n");
        last = t;
    }
    if (when(w.end) > last) out.put(fmt::format("#{}\n", when(w.end)));
    out.commit();
}

void writeCsv(const Waveform& w, const std::string& path, CsvDialect dialect) {
    const bool dense = dialect != CsvDialect::SaleaeLogic2;
    if (dense && (w.timebase.num <= 0 || w.timebase.den % w.timebase.num != 0))
        throw std::invalid_argument(
            "writeCsv: a dense CSV needs a timebase of one sample per tick");
    const std::int64_t rate = w.timebase.den / w.timebase.num;
    AtomicFile out(path);
    std::vector<std::uint8_t> level(w.names.size(), 1);
    for (std::size_t i = 0; i < w.names.size() && i < w.initial.size(); ++i)
        level[i] = w.initial[i];
    auto rowValues = [&](std::string& row) {
        for (std::size_t i = 0; i < level.size(); ++i) {
            row += level[i] ? '1' : '0';
            row += i + 1 < level.size() ? ',' : '\n';
        }
    };
    std::vector<std::string> names;
    for (const auto& n : w.names)
        names.push_back(safeName(n));

    if (dialect == CsvDialect::SaleaeLogic2) {
        // Enough decimals to write every tick exactly (at least 9, as Logic 2 does).
        int digits = -1;
        for (int d = 9; d <= 15 && digits < 0; ++d)
            if ((__int128)w.timebase.num * pow10(d) % w.timebase.den == 0) digits = d;
        if (digits < 0) digits = 12;
        out.put(fmt::format("Time [s],{}\n", fmt::join(names, ",")));
        std::string row;
        auto emit = [&](Tick t) {
            row = decimalSeconds(scaled(t, w.timebase, digits), digits) + ",";
            rowValues(row);
            out.put(row);
        };
        emit(w.start);
        Tick last = w.start;
        for (std::size_t k = 0; k < w.edges.size();) {
            const Tick t = w.edges[k].t;
            for (; k < w.edges.size() && w.edges[k].t == t; ++k)
                level[w.edges[k].line] = w.edges[k].level;
            emit(t);
            last = t;
        }
        if (w.end > last) emit(w.end);  // so the capture's length survives
        out.commit();
        return;
    }

    if (dialect == CsvDialect::SigrokDense) {
        out.put("; CSV generated by busdecode\n");
        out.put(fmt::format("; Channels ({}/{}): {}\n", names.size(), names.size(),
                            fmt::join(names, ", ")));
        out.put(fmt::format("; Samplerate: {}\n", sampleRateText(rate)));
        std::vector<std::string> logic(names.size(), "logic");
        out.put(fmt::format("{}\n", fmt::join(logic, ",")));
    } else {
        out.put(fmt::format("{}\n", fmt::join(names, ",")));
    }
    std::size_t k = 0;
    std::string row;
    for (Tick t = w.start; t <= w.end; ++t) {
        for (; k < w.edges.size() && w.edges[k].t <= t; ++k)
            level[w.edges[k].line] = w.edges[k].level;
        row.clear();
        rowValues(row);
        out.put(row);
    }
    out.commit();
}

}  // namespace busdecode
