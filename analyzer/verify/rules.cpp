#include "rules.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <toml++/toml.h>

#include "capture/readers.h"
#include "core/options.h"
#include "core/sample_rate.h"

namespace busdecode {

namespace {

const std::vector<std::string> kRuleKeys = {
    "max_crc_errors", "max_errors", "max_warnings",      "max_repeat_mismatches", "max_faults",
    "min_frames",     "clock_hz",   "max_line_delay_ns", "max_proc_cycles",       "tm_us",
    "timeout_us",     "position",   "max_position_jump", "position_modulus",      "registers"};

const std::vector<std::string> kSignalRuleKeys = {"min_swing_v", "max_rise_ns", "max_fall_ns",
                                                  "max_overshoot_pct"};

const std::vector<std::string> kDecodeKeys = {"proto", "map", "opt", "rate"};

// toml++ keeps a table's keys sorted; rules are reported in the order the file gives them.
std::vector<std::pair<const toml::key*, const toml::node*>> inFileOrder(const toml::table& t) {
    std::vector<std::pair<const toml::key*, const toml::node*>> out;
    for (auto&& [k, v] : t)
        out.emplace_back(&k, &v);
    std::stable_sort(out.begin(), out.end(), [](const auto& a, const auto& b) {
        const auto& x = a.first->source().begin;
        const auto& y = b.first->source().begin;
        return x.line != y.line ? x.line < y.line : x.column < y.column;
    });
    return out;
}

std::string typeName(const toml::node& n) {
    if (n.is_string()) return "a string";
    if (n.is_integer()) return "an integer";
    if (n.is_floating_point()) return "a float";
    if (n.is_boolean()) return "a boolean";
    if (n.is_array()) return "an array";
    if (n.is_table()) return "a table";
    return "a date/time";
}

// Errors point at the key's (or value's) line: "rules.toml:7: [bissc] clock_hz: ...".
class RulesReader {
public:
    RulesReader(std::string file) : file_(std::move(file)) {}

    [[noreturn]] void fail(const toml::source_region& where, const std::string& table,
                           const std::string& key, const std::string& msg) const {
        const std::string place = table.empty() ? key : fmt::format("[{}] {}", table, key);
        // Keys may hold any character (quoted keys): keep the message on one line.
        throw InputError(fmt::format("{}:{}: {}: {}", file_, where.begin.line, printable(place, 80),
                                     printable(msg, 300)));
    }

    double number(const toml::node& n, const std::string& table, const std::string& key) const {
        if (!n.is_number())
            fail(n.source(), table, key, fmt::format("expected a number, got {}", typeName(n)));
        // An integer past 2^53 (9223372036854775807) has no exact double: still a number.
        const double v =
            n.is_integer() ? double(n.as_integer()->get()) : n.value<double>().value_or(NAN);
        if (!std::isfinite(v)) fail(n.source(), table, key, "expected a finite number");
        return v;
    }

    double nonNegative(const toml::node& n, const std::string& table,
                       const std::string& key) const {
        const double v = number(n, table, key);
        if (v < 0) fail(n.source(), table, key, fmt::format("must not be negative, got {}", v));
        return v;
    }

    std::int64_t count(const toml::node& n, const std::string& table,
                       const std::string& key) const {
        const double v = number(n, table, key);
        if (v < 0 || v != std::floor(v) || v > 9.0e18)
            fail(n.source(), table, key, fmt::format("expected a whole number >= 0, got {}", v));
        return std::int64_t(v);
    }

    RuleRange range(const toml::node& n, const std::string& table, const std::string& key,
                    bool non_negative) const {
        const toml::array* a = n.as_array();
        if (!a || a->size() != 2)
            fail(n.source(), table, key,
                 fmt::format("expected [min, max], got {}",
                             a ? fmt::format("an array of {}", a->size()) : typeName(n)));
        RuleRange r{number(*a->get(0), table, key), number(*a->get(1), table, key)};
        if (r.min > r.max)
            fail(n.source(), table, key,
                 fmt::format("impossible range: min {} is above max {}", r.min, r.max));
        if (non_negative && r.min < 0)
            fail(n.source(), table, key,
                 fmt::format("impossible range: min {} is negative", r.min));
        return r;
    }

    std::map<std::int64_t, std::int64_t> registers(const toml::node& n,
                                                   const std::string& table) const {
        const toml::table* t = n.as_table();
        if (!t)
            fail(n.source(), table, "registers",
                 fmt::format("expected a table of address = value, got {}", typeName(n)));
        std::map<std::int64_t, std::int64_t> out;
        for (auto [kp, vp] : inFileOrder(*t)) {
            const toml::key& k = *kp;
            const toml::node& v = *vp;
            const std::string key = "registers." + std::string(k.str());
            const auto addr = parseInteger(std::string(k.str()));
            if (!addr || *addr < 0)
                fail(k.source(), table, key, "the key must be a register address (e.g. \"0x78\")");
            out[*addr] = count(v, table, key);
        }
        return out;
    }

    ProtoRules protoTable(const std::string& name, const toml::table& t, int line) const {
        ProtoRules r;
        r.proto = name;
        r.line = line;
        // A table that checks nothing would pass every capture: most likely a mistake.
        const auto& valid = name == kSignalTable ? kSignalRuleKeys : kRuleKeys;
        if (t.empty())
            throw InputError(
                fmt::format("{}:{}: [{}]: no rules in this table (it would check "
                            "nothing; valid keys: {})",
                            file_, line, printable(name, 80), fmt::join(valid, ", ")));
        for (auto [kp, vp] : inFileOrder(t)) {
            const toml::key& k = *kp;
            const toml::node& v = *vp;
            const std::string key(k.str());
            if (std::find(valid.begin(), valid.end(), key) == valid.end())
                fail(k.source(), name, key,
                     fmt::format("unknown key (valid: {})", fmt::join(valid, ", ")));
            r.keys.push_back(key);
            if (key == "min_swing_v")
                r.min_swing_v = nonNegative(v, name, key);
            else if (key == "max_rise_ns")
                r.max_rise_ns = nonNegative(v, name, key);
            else if (key == "max_fall_ns")
                r.max_fall_ns = nonNegative(v, name, key);
            else if (key == "max_overshoot_pct")
                r.max_overshoot_pct = nonNegative(v, name, key);
            else if (key == "max_crc_errors")
                r.max_crc_errors = count(v, name, key);
            else if (key == "max_errors")
                r.max_errors = count(v, name, key);
            else if (key == "max_warnings")
                r.max_warnings = count(v, name, key);
            else if (key == "max_repeat_mismatches")
                r.max_repeat_mismatches = count(v, name, key);
            else if (key == "max_faults")
                r.max_faults = count(v, name, key);
            else if (key == "min_frames")
                r.min_frames = count(v, name, key);
            else if (key == "clock_hz") {
                r.clock_hz = range(v, name, key, true);
                if (r.clock_hz->max <= 0)
                    fail(v.source(), name, key, "impossible range: max must be above 0 Hz");
            } else if (key == "max_line_delay_ns")
                r.max_line_delay_ns = nonNegative(v, name, key);
            else if (key == "max_proc_cycles")
                r.max_proc_cycles = nonNegative(v, name, key);
            else if (key == "tm_us")
                r.tm_us = range(v, name, key, true);
            else if (key == "timeout_us")
                r.timeout_us = range(v, name, key, true);
            else if (key == "position")
                r.position = range(v, name, key, false);
            else if (key == "max_position_jump")
                r.max_position_jump = nonNegative(v, name, key);
            else if (key == "position_modulus")
                r.position_modulus = nonNegative(v, name, key);
            else if (key == "registers")
                r.registers = registers(v, name);
        }
        return r;
    }

    // "map"/"opt": a table (nested tables flatten to dotted keys) or an array of "K=V".
    void pairs(const toml::node& n, const std::string& key, const std::string& prefix,
               std::vector<std::string>& out) const {
        if (const toml::array* a = n.as_array()) {
            for (const auto& item : *a) {
                auto s = item.value<std::string>();
                if (!s || s->find('=') == std::string::npos)
                    fail(item.source(), "decode", key, "array items must be strings KEY=VALUE");
                out.push_back(*s);
            }
            return;
        }
        const toml::table* t = n.as_table();
        if (!t)
            fail(n.source(), "decode", key,
                 fmt::format("expected a table or an array of \"KEY=VALUE\", got {}", typeName(n)));
        for (auto [kp, vp] : inFileOrder(*t)) {
            const toml::key& k = *kp;
            const toml::node& v = *vp;
            const std::string name = prefix + std::string(k.str());
            if (v.is_table()) {
                pairs(v, key, name + ".", out);
            } else if (auto s = v.value_exact<std::string>()) {
                out.push_back(name + "=" + *s);
            } else if (auto b = v.value_exact<bool>()) {
                out.push_back(name + "=" + (*b ? "1" : "0"));
            } else if (auto i = v.value_exact<std::int64_t>()) {
                out.push_back(fmt::format("{}={}", name, *i));
            } else if (auto d = v.value_exact<double>()) {
                out.push_back(fmt::format("{}={}", name, *d));
            } else {
                fail(v.source(), "decode", key + "." + name,
                     fmt::format("expected a string, number or boolean, got {}", typeName(v)));
            }
        }
    }

    DecodeDefaults decodeTable(const toml::table& t) const {
        DecodeDefaults d;
        for (auto [kp, vp] : inFileOrder(t)) {
            const toml::key& k = *kp;
            const toml::node& v = *vp;
            const std::string key(k.str());
            if (key == "proto") {
                if (auto s = v.value_exact<std::string>()) {
                    d.protos.push_back(*s);
                } else if (const toml::array* a = v.as_array()) {
                    for (const auto& item : *a) {
                        auto s2 = item.value_exact<std::string>();
                        if (!s2)
                            fail(item.source(), "decode", key, "expected decoder ids as strings");
                        d.protos.push_back(*s2);
                    }
                } else {
                    fail(v.source(), "decode", key,
                         fmt::format("expected a string or an array of strings, got {}",
                                     typeName(v)));
                }
            } else if (key == "map" || key == "opt") {
                pairs(v, key, "", key == "map" ? d.maps : d.opts);
            } else if (key == "rate") {
                d.rate_hz = number(v, "decode", key);
                if (d.rate_hz <= 0) fail(v.source(), "decode", key, "must be above 0 Hz");
                const SampleRate r = sampleRateOf(d.rate_hz);
                if (!r.timebase)
                    fail(v.source(), "decode", key, fmt::format("{} Hz {}", d.rate_hz, r.problem));
            } else {
                fail(k.source(), "decode", key,
                     fmt::format("unknown key (valid: {})", fmt::join(kDecodeKeys, ", ")));
            }
        }
        return d;
    }

private:
    std::string file_;
};

}  // namespace

const std::vector<std::string>& ruleKeys() {
    return kRuleKeys;
}

const std::vector<std::string>& signalRuleKeys() {
    return kSignalRuleKeys;
}

std::string primaryEventType(const std::string& proto) {
    if (proto == "ssi" || proto == "bissc") return "frame";
    if (proto == "spi") return "transfer";
    if (proto == "uart") return "byte";
    if (proto == "tmcl" || proto == "tmc8100") return "command";
    return "";
}

Rules parseRules(const std::string& text, const std::string& file_name,
                 const std::vector<std::string>& known_protos) {
    toml::table root;
    try {
        root = toml::parse(text, file_name);
    } catch (const toml::parse_error& err) {
        throw InputError(fmt::format("{}:{}:{}: {}", file_name, err.source().begin.line,
                                     err.source().begin.column,
                                     printable(err.description(), 200)));  // one line
    }
    RulesReader reader(file_name);
    Rules rules;
    rules.file = file_name;
    for (auto [kp, vp] : inFileOrder(root)) {
        const toml::key& k = *kp;
        const toml::node& v = *vp;
        const std::string name(k.str());
        const toml::table* t = v.as_table();
        if (!t)
            reader.fail(k.source(), "", name,
                        fmt::format("expected a table [{}] of rules, got {}", name, typeName(v)));
        if (name == "decode") {
            rules.decode = reader.decodeTable(*t);
            continue;
        }
        if (!known_protos.empty() && name != kSignalTable &&
            std::find(known_protos.begin(), known_protos.end(), name) == known_protos.end())
            reader.fail(k.source(), "", "[" + name + "]",
                        fmt::format("unknown decoder (known: {}, and decode, signal)",
                                    fmt::join(known_protos, ", ")));
        rules.tables.push_back(reader.protoTable(name, *t, int(k.source().begin.line)));
    }
    if (rules.tables.empty())
        throw InputError(fmt::format(
            "{}: no rules: add a table per decoder, e.g. [bissc] min_frames = 1", file_name));
    return rules;
}

Rules loadRules(const std::string& path, const std::vector<std::string>& known_protos) {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec))
        throw InputError(fmt::format("{}: is a directory, not a rules file", printable(path, 200)));
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(fmt::format("{}: cannot read the rules file", path));
    std::ostringstream ss;
    ss << in.rdbuf();
    return parseRules(ss.str(), path, known_protos);
}

}  // namespace busdecode
