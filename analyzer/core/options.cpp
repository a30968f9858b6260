#include "options.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>

#include <fmt/format.h>
#include <fmt/ranges.h>

namespace busdecode {

std::string oneLine(std::string_view text) {
    std::string out;
    out.reserve(text.size());
    for (const char c : text) {
        const auto u = static_cast<unsigned char>(c);
        if (u < 0x20 || u == 0x7f)
            out += fmt::format("\\x{:02x}", u);
        else
            out += c;
    }
    return out;
}

std::optional<double> parseNumber(const std::string& s) {
    if (s.empty()) return std::nullopt;
    if (auto i = parseInteger(s)) return double(*i);
    errno = 0;
    char* end = nullptr;
    double v = std::strtod(s.c_str(), &end);
    if (errno != 0 || end != s.c_str() + s.size() || !std::isfinite(v)) return std::nullopt;
    return v;
}

std::optional<std::int64_t> parseInteger(const std::string& s) {
    if (s.empty()) return std::nullopt;
    errno = 0;
    char* end = nullptr;
    long long v = std::strtoll(s.c_str(), &end, 0);  // base 0: 0x.. hex as well
    if (errno != 0 || end != s.c_str() + s.size()) return std::nullopt;
    return std::int64_t(v);
}

namespace {

std::string describe(const OptionSpec& o) {
    switch (o.kind) {
        case OptionSpec::Kind::Bool:
            return "0 or 1";
        case OptionSpec::Kind::Choice:
            return fmt::format("one of {}", fmt::join(o.choices, ", "));
        case OptionSpec::Kind::String:
            return "text";
        case OptionSpec::Kind::Int:
        case OptionSpec::Kind::Float: {
            std::string what = o.kind == OptionSpec::Kind::Int ? "an integer" : "a number";
            std::string range;
            if (o.min > -1e299 && o.max < 1e299)
                range = fmt::format(" from {} to {}", o.min, o.max);
            else if (o.min > -1e299)
                range = fmt::format(" >= {}", o.min);
            else if (o.max < 1e299)
                range = fmt::format(" <= {}", o.max);
            return what + range + (o.allow_auto ? " or auto" : "");
        }
    }
    return "";
}

std::string normalise(const DecoderInfo& info, const OptionSpec& o, const std::string& v) {
    auto bad = [&]() {
        return InputError(
            fmt::format("decoder {}: option {}={}: expected {}", info.id, o.key, v, describe(o)));
    };
    switch (o.kind) {
        case OptionSpec::Kind::Bool: {
            if (v == "1" || v == "true" || v == "yes" || v == "on") return "1";
            if (v == "0" || v == "false" || v == "no" || v == "off") return "0";
            throw bad();
        }
        case OptionSpec::Kind::Choice:
            for (const auto& c : o.choices)
                if (c == v) return v;
            throw bad();
        case OptionSpec::Kind::String:
            return v;
        case OptionSpec::Kind::Int: {
            if (o.allow_auto && v == "auto") return v;
            auto i = parseInteger(v);
            if (!i) {
                // Accept 1e6-style integers.
                auto d = parseNumber(v);
                if (!d || std::floor(*d) != *d || std::fabs(*d) > 9e18) throw bad();
                i = std::int64_t(*d);
            }
            if (double(*i) < o.min || double(*i) > o.max) throw bad();
            return std::to_string(*i);
        }
        case OptionSpec::Kind::Float: {
            if (o.allow_auto && v == "auto") return v;
            auto d = parseNumber(v);
            if (!d || *d < o.min || *d > o.max) throw bad();
            return v;
        }
    }
    throw bad();
}

}  // namespace

Options Options::resolve(const DecoderInfo& info, const std::map<std::string, std::string>& given) {
    Options out;
    for (const auto& o : info.options)
        if (!o.default_value.empty()) out.values_[o.key] = normalise(info, o, o.default_value);
    for (const auto& [k, v] : given) {
        const OptionSpec* spec = nullptr;
        for (const auto& o : info.options)
            if (o.key == k) spec = &o;
        if (!spec) {
            std::vector<std::string> keys;
            for (const auto& o : info.options)
                keys.push_back(o.key);
            throw InputError(fmt::format("decoder {}: unknown option '{}' (valid: {})", info.id, k,
                                         fmt::join(keys, ", ")));
        }
        out.values_[k] = normalise(info, *spec, v);
    }
    return out;
}

const std::string& Options::text(const std::string& key) const {
    static const std::string empty;
    auto it = values_.find(key);
    return it == values_.end() ? empty : it->second;
}

std::int64_t Options::integer(const std::string& key) const {
    auto v = parseInteger(text(key));
    if (v) return *v;
    auto d = parseNumber(text(key));
    return d ? std::int64_t(*d) : 0;
}

double Options::number(const std::string& key) const {
    auto d = parseNumber(text(key));
    return d ? *d : 0.0;
}

bool Options::flag(const std::string& key) const {
    return text(key) == "1";
}

}  // namespace busdecode
