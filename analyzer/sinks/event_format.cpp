#include "event_format.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include <fmt/compile.h>
#include <fmt/format.h>

#include "core/number_text.h"
#include "core/utf8.h"

namespace busdecode {

namespace {

void appendJsonString(std::string& out, const std::string& s) {
    out += '"';
    for (std::size_t i = 0; i < s.size(); ++i) {
        const auto c = static_cast<unsigned char>(s[i]);
        switch (c) {
            case '"':
                out += "\\\"";
                break;
            case '\\':
                out += "\\\\";
                break;
            case '\n':
                out += "\\n";
                break;
            case '\r':
                out += "\\r";
                break;
            case '\t':
                out += "\\t";
                break;
            default:
                if (c < 0x20)
                    out += fmt::format("\\u{:04x}", c);
                else if (c < 0x80)
                    out += char(c);
                else
                    i += appendUtf8OrReplacement(out, s, i) - 1;
        }
    }
    out += '"';
}

void appendValue(std::string& out, const Value& v) {
    std::visit(
        [&](const auto& x) {
            using T = std::decay_t<decltype(x)>;
            if constexpr (std::is_same_v<T, Null>)
                out += "null";
            else if constexpr (std::is_same_v<T, bool>)
                out += x ? "true" : "false";
            else if constexpr (std::is_same_v<T, std::int64_t> || std::is_same_v<T, std::uint64_t>)
                appendDecimal(out, x);
            else if constexpr (std::is_same_v<T, double>) {
                switch (jsonNumberKind(x)) {
                    case JsonNumber::Null:
                        out += "null";
                        break;
                    case JsonNumber::Integer:
                        appendDecimal(out, std::int64_t(x));
                        break;
                    case JsonNumber::Real:
                        fmt::format_to(std::back_inserter(out), "{}", x);
                }
            } else if constexpr (std::is_same_v<T, std::string>)
                appendJsonString(out, x);
            else {
                out += '[';
                for (std::size_t i = 0; i < x.size(); ++i) {
                    if (i) out += ',';
                    appendDecimal(out, x[i]);
                }
                out += ']';
            }
        },
        v);
}

// ns as seconds with 9 decimals, right-aligned in 14 columns: what "{:>14.9f}" makes of
// ns / 1e9, from integers (a double conversion per event costs more than the rest of
// the line).
void appendSeconds(std::string& out, std::int64_t ns) {
    constexpr std::int64_t kExact = 1'000'000'000'000'000;  // below this the two agree
    if (ns <= -kExact || ns >= kExact) {
        fmt::format_to(std::back_inserter(out), FMT_COMPILE("{:>14.9f}"), double(ns) / 1e9);
        return;
    }
    // "{:>14}" of "{}{}.{:09}": built in a buffer, pieces copied, one append (about 140
    // instructions fewer per output line than fmt's compiled format, by callgrind).
    const std::int64_t mag = ns < 0 ? -ns : ns;
    const fmt::format_int whole(mag / 1'000'000'000), frac(mag % 1'000'000'000);
    char line[32];
    char* p = line;
    if (ns < 0) *p++ = '-';
    std::memcpy(p, whole.data(), whole.size());
    p += whole.size();
    *p++ = '.';
    std::memset(p, '0', 9 - frac.size());
    std::memcpy(p + 9 - frac.size(), frac.data(), frac.size());
    p += 9;
    const std::size_t len = std::size_t(p - line);
    if (len < 14) out.append(14 - len, ' ');
    out.append(line, len);
}

std::string valueToText(const Value& v) {
    if (auto s = std::get_if<std::string>(&v)) return *s;
    if (auto b = std::get_if<bool>(&v)) return *b ? "1" : "0";
    if (auto d = std::get_if<double>(&v))
        return std::isfinite(*d) ? fmt::format("{:.6g}", *d) : "-";
    return valueToJson(v);
}

}  // namespace

std::string valueToJson(const Value& v) {
    std::string out;
    appendValue(out, v);
    return out;
}

std::string eventToJson(const Event& e, const Timebase& tb, std::string_view capture_fields) {
    std::string out;
    out.reserve(256);
    appendEventJson(out, e, tb, capture_fields);
    return out;
}

std::string captureJsonFields(const CaptureFacts& facts, bool name_capture) {
    std::string out;
    if (name_capture) {
        out += ",\"capture\":";
        appendJsonString(out, facts.file);
    }
    if (!facts.capture_start.empty()) {
        out += ",\"capture_start\":";
        appendJsonString(out, facts.capture_start);
    }
    return out;
}

void appendEventJson(std::string& out, const Event& e, const Timebase& tb,
                     std::string_view capture_fields) {
    out += "{\"proto\":";
    appendJsonString(out, e.proto);
    out += ",\"type\":";
    appendJsonString(out, e.type);
    out += capture_fields;
    fmt::format_to(std::back_inserter(out), ",\"start_ns\":{},\"end_ns\":{}", tb.toNs(e.start),
                   tb.toNs(e.end));
    for (const auto& f : e.fields) {
        if (isCommonEventKey(f.key)) continue;
        out += ',';
        appendJsonString(out, f.key);
        out += ':';
        appendValue(out, f.value);
    }
    out += ",\"errors\":[";
    for (std::size_t i = 0; i < e.errors.size(); ++i) {
        if (i) out += ',';
        appendJsonString(out, e.errors[i]);
    }
    out += "]}";
}

std::string formatDuration(double ns) {
    const double a = std::fabs(ns);
    if (a >= 1e9) return fmt::format("{:.6f} s", ns / 1e9);
    if (a >= 1e6) return fmt::format("{:.3f} ms", ns / 1e6);
    if (a >= 1e3) return fmt::format("{:.3f} us", ns / 1e3);
    if (a >= 1 || a == 0) return fmt::format("{:.0f} ns", ns);
    // A VCD's timescale goes down to 1 fs.
    if (a >= 1e-3) return fmt::format("{:.0f} ps", ns * 1e3);
    return fmt::format("{:.0f} fs", ns * 1e6);
}

std::string eventToText(const Event& e, const Timebase& tb) {
    std::string line;
    appendEventText(line, e, tb);
    return line;
}

void appendEventText(std::string& out, const Event& e, const Timebase& tb) {
    appendSeconds(out, tb.toNs(e.start));
    // " s  {:<8} {:<12} " in one piece: blanks, then the names copied over them (four
    // appends and two paddings cost about 250 instructions more per line, by callgrind).
    // The names are ASCII: fmt would measure their width code point by code point.
    const std::string& name = e.instance.empty() ? e.proto : e.instance;
    const std::size_t name_width = std::max<std::size_t>(name.size(), 8);
    const std::size_t type_width = std::max<std::size_t>(e.type.size(), 12);
    const std::size_t at = out.size();
    out.resize(at + 4 + name_width + 1 + type_width + 1, ' ');
    char* const head = out.data() + at;
    head[1] = 's';
    std::memcpy(head + 4, name.data(), name.size());
    std::memcpy(head + 4 + name_width + 1, e.type.data(), e.type.size());
    if (!e.summary.empty()) {
        out += e.summary;
    } else {
        bool first = true;
        for (const auto& f : e.fields) {
            if (!first) out += ' ';
            first = false;
            out += f.key;
            out += '=';
            out += valueToText(f.value);
        }
    }
    if (!e.errors.empty()) {
        out += "  !";
        for (std::size_t i = 0; i < e.errors.size(); ++i) {
            if (i) out += ',';
            out += e.errors[i];
        }
    }
}

}  // namespace busdecode
