// Each scope's header, as FORMATS.md quotes it, turned into a ScopeLayout. Only the
// first lines decide; the rows are read by ScopeCsvReader.
#include "scope_csv_layout.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstring>

#include <fmt/format.h>

#include "core/options.h"
#include "csv_fields.h"

namespace busdecode {

namespace {

bool startsWith(std::string_view s, std::string_view p) {
    return s.substr(0, p.size()) == p;
}

using Fields = std::vector<std::string_view>;

Fields splitFields(std::string_view line, char sep) {
    Fields out;
    std::size_t b = 0;
    for (;;) {
        const std::size_t e = line.find(sep, b);
        out.push_back(trimField(line.substr(b, e == std::string_view::npos ? e : e - b)));
        if (e == std::string_view::npos) return out;
        b = e + 1;
    }
}

// The complete lines of the head (the last, cut off by the peek, left out).
std::vector<std::string_view> headLines(std::string_view head, bool whole) {
    std::vector<std::string_view> lines;
    std::size_t b = 0;
    for (std::size_t e; (e = head.find('\n', b)) != std::string_view::npos; b = e + 1)
        lines.push_back(trimBlanks(head.substr(b, e - b)));
    if (whole && b < head.size()) lines.push_back(trimBlanks(head.substr(b)));
    return lines;
}

// Volts per unit of a voltage unit ("mV", "(mV)", "µV"); 0 for any other text.
double voltsPerUnit(std::string_view unit) {
    if (unit.size() > 2 && unit.front() == '(' && unit.back() == ')')
        unit = unit.substr(1, unit.size() - 2);
    const std::string u = asciiLower(trimField(unit));
    return u == "v"                                                            ? 1
           : u == "mv"                                                         ? 1e-3
           : u == "uv" || u == "\xc2\xb5v" || u == "\xce\xbcv" || u == "\xb5v" ? 1e-6
           : u == "kv"                                                         ? 1e3
                                                                               : 0;
}

// PicoScope's channel titles, English and German ("Kanal A"): the prefix's length, or 0.
std::size_t picoChannelPrefix(std::string_view title) {
    const std::string lower = asciiLower(title);
    for (std::string_view prefix : {"channel ", "kanal "})
        if (startsWith(lower, prefix)) return prefix.size();
    return 0;
}

// "X(CH2)" -> CH2, "CH 1 (V)" -> CH1, "Channel A" -> A, "1" (Keysight) -> CH1.
std::string channelName(std::string_view title) {
    std::string_view t = title;
    if (const auto open = t.find('('); open != std::string_view::npos && t.back() == ')') {
        const std::string_view inner = t.substr(open + 1, t.size() - open - 2);
        t = voltsPerUnit(inner) > 0 ? trimField(t.substr(0, open)) : inner;
    }
    if (const std::size_t prefix = picoChannelPrefix(t))
        return std::string(trimField(t.substr(prefix)));
    std::string out;
    for (char c : t)
        if (c != ' ') out += c;
    if (!out.empty() && std::all_of(out.begin(), out.end(), ::isdigit)) out = "CH" + out;
    return out;
}

// "CH 1 (mV)" -> 1e-3; a title without a voltage unit is in volts.
double titleScale(std::string_view title) {
    const auto open = title.find('(');
    const double scale = open == std::string_view::npos ? 0 : voltsPerUnit(title.substr(open));
    return scale > 0 ? scale : 1;
}

void addChannels(ScopeLayout& l, const Fields& f, std::size_t from, std::size_t to) {
    for (std::size_t i = from; i < to && i < f.size(); ++i) {
        if (f[i].empty() && i + 1 == f.size()) break;  // a trailing separator
        l.channels.push_back({channelName(f[i]), std::string(f[i]), i, -1, titleScale(f[i])});
    }
}

// Rigol's logic analyser columns: "D7-D0" (bit n = Dn) and "D15-D8" (bit n = D(8+n)).
bool addByteColumn(ScopeLayout& l, std::string_view title, std::size_t field) {
    int hi = 0, lo = 0;
    if (title.size() < 5 || title[0] != 'D') return false;
    const auto dash = title.find("-D");
    if (dash == std::string_view::npos) return false;
    auto [p1, e1] = std::from_chars(title.data() + 1, title.data() + dash, hi);
    auto [p2, e2] = std::from_chars(title.data() + dash + 2, title.data() + title.size(), lo);
    if (e1 != std::errc() || e2 != std::errc() || hi - lo != 7 || lo % 8 != 0) return false;
    // Each bit is named on its own: "D7-D0" names no single line.
    for (int b = 0; b < 8; ++b)
        l.channels.push_back({fmt::format("D{}", lo + b), fmt::format("D{}", lo + b), field, b});
    return true;
}

[[noreturn]] void broken(const std::string& name, std::size_t line, const std::string& what) {
    throw InputError(fmt::format("{}:{}: {}", name, line, what));
}

// DS1000Z/DS2000/DS4000: "X,CH1,CH2,Start,Increment," then "Sequence,Volt,Volt,START,INC".
std::optional<ScopeLayout> rigolIndexed(const std::vector<std::string_view>& lines,
                                        const std::string& name) {
    const Fields f = splitFields(lines[0], ',');
    const auto start = std::find(f.begin(), f.end(), "Start");
    if (f[0] != "X" || start == f.end() || start + 1 == f.end() || start[1] != "Increment")
        return std::nullopt;
    const std::size_t at = std::size_t(start - f.begin());
    ScopeLayout l;
    l.format = "rigol-csv";
    l.header_lines = 2;
    l.fields = at;
    l.time_is_index = true;
    if (lines.size() < 2) broken(name, 1, "Rigol CSV without its units row (Sequence,Volt,...)");
    const Fields u = splitFields(lines[1], ',');
    if ((u[0] != "Sequence" && u[0] != "Counter") || u.size() < at + 2 ||
        !parseScopeNumber(u[at], false, l.start) ||
        !parseScopeNumber(u[at + 1], false, l.increment) || !(l.increment > 0))
        broken(name, 2,
               "expected Rigol's units row 'Sequence,Volt,...,START,INCREMENT' after 'X,CH1,...'");
    for (std::size_t i = 1; i < at; ++i)
        if (!addByteColumn(l, f[i], i))
            l.channels.push_back({channelName(f[i]), std::string(f[i]), i, -1});
    return l;
}

// A time column in seconds, named on line 1, with a units row "Second,Volt" (Rigol
// DS1000E/B/D, Keysight "x-axis"), or without one (Rigol DS1102D "X,CH 1 (V)").
std::optional<ScopeLayout> timeAndUnits(const std::vector<std::string_view>& lines,
                                        const std::string& name) {
    const Fields f = splitFields(lines[0], ',');
    const std::string first = asciiLower(f[0]);
    const bool keysight = first == "x-axis";
    const bool second_row =
        lines.size() > 1 && asciiLower(splitFields(lines[1], ',')[0]) == "second";
    if (!keysight && !((first == "x" || first == "time" || first.empty()) && second_row) &&
        !(f[0] == "X" && f.size() > 1 && startsWith(f[1], "CH")))
        return std::nullopt;
    if (keysight && !second_row)
        broken(name, 2, "expected the units row 'second,Volt,...' after 'x-axis,...'");
    ScopeLayout l;
    l.format = keysight ? "keysight-csv" : "rigol-csv";
    l.header_lines = second_row ? 2 : 1;
    addChannels(l, f, 1, f.size());
    l.fields = l.channels.size() + 1;
    return l;
}

std::size_t lineStarting(const std::vector<std::string_view>& lines, std::string_view prefix) {
    for (std::size_t i = 0; i < lines.size(); ++i)
        if (startsWith(lines[i], prefix)) return i;
    return lines.size();
}

// LeCroy's "Segments,N,SegmentSize,M" and its N "#k,TrigTime,TimeSinceSegment1" lines
// before `header_at`: every segment, shifted to its trigger's time.
void lecroySegments(const std::vector<std::string_view>& lines, std::size_t header_at,
                    const std::string& name, ScopeLayout& l) {
    const Fields f = splitFields(lines[1], ',');
    double n = 0, rows = 0;
    if (f.size() < 4 || f[2] != "SegmentSize" || !parseScopeNumber(f[1], false, n) ||
        !parseScopeNumber(f[3], false, rows) || n < 1 || rows < 1 || n != std::floor(n) ||
        rows != std::floor(rows))
        broken(name, 2, "expected LeCroy's 'Segments,COUNT,SegmentSize,ROWS'");
    if (n == 1) return;
    for (std::size_t i = 2; i < header_at; ++i) {
        if (!startsWith(lines[i], "#")) continue;
        const Fields s = splitFields(lines[i], ',');
        double since = 0;
        if (s.size() < 3 || !parseScopeNumber(s[2], false, since) || !std::isfinite(since))
            broken(name, i + 1, "expected a segment line '#K,TRIGTIME,SECONDS_SINCE_SEGMENT_1'");
        l.segment_starts.push_back(since);
    }
    if (double(l.segment_starts.size()) != n)
        broken(name, header_at + 1,
               fmt::format("LeCroy file of {} segments lists {} segment lines before 'Time,'", n,
                           l.segment_starts.size()));
    l.segment_rows = std::size_t(rows);
}

// A key/value block, then a column header row: Tektronix MSO/MDO ("TIME,CH1,CH2"), Rigol's
// PC software ("Time (s)",...), Siglent ("Second,Volt"), LeCroy ("Time,Ampl").
std::optional<ScopeLayout> blockThenHeader(const std::vector<std::string_view>& lines,
                                           const std::string& name) {
    const std::string_view l0 = lines[0];
    std::string format, header;
    if (startsWith(l0, "Model,") || startsWith(l0, "Waveform Type,"))
        format = "tektronix-csv", header = "TIME,";
    else if (startsWith(l0, "\"Number of Data points"))
        format = "rigol-csv", header = "\"Time (s)\"";
    else if (startsWith(l0, "Record Length,Analog:"))
        format = "siglent-csv", header = "Second,";
    else if (l0.find(",Waveform") != std::string_view::npos && lines.size() > 1 &&
             startsWith(lines[1], "Segments,"))
        format = "lecroy-csv", header = "Time,";
    else
        return std::nullopt;
    const std::size_t at = lineStarting(lines, header);
    if (at == lines.size())
        broken(name, lines.size(),
               fmt::format("{} header without its column row '{}...'", format, header));
    ScopeLayout l;
    l.format = format;
    l.header_lines = at + 1;
    const Fields f = splitFields(lines[at], ',');
    const std::size_t names_at =
        lineStarting(lines, format == "siglent-csv" ? "Source," : "\"Channel Data\"");
    if (names_at < at && format != "tektronix-csv") {
        const Fields n = splitFields(lines[names_at], ',');
        for (std::size_t i = 1; i < f.size() && i < n.size(); ++i)
            l.channels.push_back({channelName(n[i]), std::string(n[i]), i, -1});
    } else {
        addChannels(l, f, 1, f.size());
    }
    l.fields = l.channels.size() + 1;
    if (format == "lecroy-csv") lecroySegments(lines, at, name, l);
    return l;
}

// Tektronix TDS/TBS: six fields a row, "label,value,unit,time,value,"; data in 3 and 4.
std::optional<ScopeLayout> tektronixSpreadsheet(const std::vector<std::string_view>& lines) {
    const Fields f = splitFields(lines[0], ',');
    if (f[0] != "Record Length" || f.size() < 5) return std::nullopt;
    ScopeLayout l;
    l.format = "tektronix-csv";
    l.fields = 5;
    l.time_field = 3;
    std::string source = "CH1";
    const std::size_t at = lineStarting(lines, "Source,");
    if (at < lines.size()) source = std::string(splitFields(lines[at], ',')[1]);
    l.channels.push_back({channelName(source), source, 4, -1});
    return l;
}

// PicoScope 6 and 7: "Time;Channel A" then a units row in parentheses, "(ms);(V)"; a German
// export's "Zeit;Kanal A".
std::optional<ScopeLayout> picoscope(const std::vector<std::string_view>& lines,
                                     const std::string& name) {
    const char sep = lines[0].find(';') != std::string_view::npos ? ';' : ',';
    const Fields f = splitFields(lines[0], sep);
    if ((f[0] != "Time" && f[0] != "Zeit") || f.size() < 2 || !picoChannelPrefix(f[1]))
        return std::nullopt;
    const Fields u = lines.size() > 1 ? splitFields(lines[1], sep) : Fields{};
    if (u.empty() || u[0].size() < 3 || u[0].front() != '(' || u[0].back() != ')')
        broken(name, 2, "expected PicoScope's units row '(ms);(V);...' after 'Time;Channel A;...'");
    const std::string unit = asciiLower(u[0].substr(1, u[0].size() - 2));
    ScopeLayout l;
    l.format = "picoscope-csv";
    l.sep = sep;
    l.decimal_comma = sep == ';';
    l.header_lines = 2;
    l.time_scale = unit == "s"    ? 1
                   : unit == "ms" ? 1e-3
                   : unit == "us" || unit == "\xc2\xb5s" || unit == "\xce\xbcs" ||
                           unit == "\xb5s"  // a Latin-1 export's µ
                       ? 1e-6
                       : unit == "ns" ? 1e-9 : 0;
    if (l.time_scale == 0)
        broken(name, 2, fmt::format("unknown time unit '({})' in PicoScope's units row", unit));
    addChannels(l, f, 1, f.size());
    // Each channel's unit is its own: "(mV)" on one range, "(V)" on another.
    for (auto& c : l.channels)
        if (c.field < u.size() && voltsPerUnit(u[c.field]) > 0) c.scale = voltsPerUnit(u[c.field]);
    l.fields = l.channels.size() + 1;
    return l;
}

}  // namespace

bool parseScopeNumber(std::string_view s, bool decimal_comma, double& out) {
    while (!s.empty() && s.front() == ' ')
        s.remove_prefix(1);
    while (!s.empty() && (s.back() == ' ' || s.back() == '\r'))
        s.remove_suffix(1);
    if (!s.empty() && s.front() == '+') s.remove_prefix(1);
    // PicoScope writes an over-range sample as "∞" or "-∞": far beyond any level, as
    // Keysight's 9.9E+37, and left out of the levels like it.
    if (s == "\xe2\x88\x9e" || s == "-\xe2\x88\x9e") {
        out = s.front() == '-' ? -9.9e37 : 9.9e37;
        return true;
    }
    if (s.size() > 2 && s[0] == '0' && (s[1] == 'x' || s[1] == 'X')) {
        unsigned v = 0;
        const auto [p, ec] = std::from_chars(s.data() + 2, s.data() + s.size(), v, 16);
        out = v;
        return ec == std::errc() && p == s.data() + s.size();
    }
    char buf[64];
    if (decimal_comma && s.size() < sizeof buf && s.find(',') != std::string_view::npos) {
        std::memcpy(buf, s.data(), s.size());
        std::replace(buf, buf + s.size(), ',', '.');
        s = std::string_view(buf, s.size());
    }
    const auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
    return !s.empty() && ec == std::errc() && p == s.data() + s.size();
}

std::optional<ScopeLayout> recogniseScopeCsv(std::string_view head, bool whole,
                                             const std::string& name) {
    const std::vector<std::string_view> lines = headLines(head, whole);
    if (lines.empty()) return std::nullopt;
    for (auto* recognise : {+[](const std::vector<std::string_view>&l, const std::string&n) {
                                return rigolIndexed(l, n);
                            },
                            +[](const std::vector<std::string_view>&l, const std::string&n) {
                                return blockThenHeader(l, n);
                            },
                            +[](const std::vector<std::string_view>&l, const std::string&) {
                                return tektronixSpreadsheet(l);
                            },
                            +[](const std::vector<std::string_view>&l, const std::string&n) {
                                return picoscope(l, n);
                            },
                            +[](const std::vector<std::string_view>&l, const std::string&n) {
                                return timeAndUnits(l, n);
                            }})
        if (auto layout = recognise(lines, name)) {
            if (layout->channels.empty())
                broken(name, layout->header_lines, "scope CSV without channel columns");
            return layout;
        }
    return std::nullopt;
}

}  // namespace busdecode
