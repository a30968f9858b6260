#pragma once
// The rules of `decode verify`, read from TOML: one table per decoder id (the table
// applies to events of that decoder), each key a limit, plus an optional [decode] table
// with --proto/--map/--opt defaults for the batch. See README "Rules for verify".
//
// Every key is checked here: an unknown key, a wrong type or an impossible range is an
// InputError naming the file, the line and the key.
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace busdecode {

struct RuleRange {
    double min = 0, max = 0;
};

struct ProtoRules {
    std::string proto;  // table name: a decoder id (or instance name)
    int line = 0;       // where the table starts in the rules file
    // Counts: the number of offending events must not exceed the limit.
    std::optional<std::int64_t> max_crc_errors;         // `crc` error or crc_ok = false
    std::optional<std::int64_t> max_errors;             // nE active (0)
    std::optional<std::int64_t> max_warnings;           // nW active (0)
    std::optional<std::int64_t> max_repeat_mismatches;  // repeat_match = false / `repeat_mismatch`
    std::optional<std::int64_t> max_faults;             // events with any error string
    std::optional<std::int64_t> min_frames;             // frames (see primaryEventType)
    // Values of every event that has the field.
    std::optional<RuleRange> clock_hz;        // clock_hz
    std::optional<double> max_line_delay_ns;  // line_delay_ns
    std::optional<double> max_proc_cycles;    // proc_cycles
    std::optional<RuleRange> tm_us;           // tm_ns / 1000 (SSI)
    std::optional<RuleRange> timeout_us;      // timeout_ns / 1000 (BiSS-C)
    std::optional<RuleRange> position;        // position
    std::optional<double> max_position_jump;  // |position - previous position|
    // Where positions wrap (0: they do not); unset: from the decoder's layout (SSI and
    // BiSS-C: 2^(st_bits + mt_bits)).
    std::optional<double> position_modulus;
    std::map<std::int64_t, std::int64_t> registers;  // address -> expected data (register events)
    // The [signal] table: limits on every analog line's `signal` event.
    std::optional<double> min_swing_v;        // swing_v
    std::optional<double> max_rise_ns;        // rise_p99_ns
    std::optional<double> max_fall_ns;        // fall_p99_ns
    std::optional<double> max_overshoot_pct;  // overshoot_pct
    std::vector<std::string> keys;            // the keys given, in file order
};

struct DecodeDefaults {
    std::vector<std::string> protos;  // --proto
    std::vector<std::string> maps;    // ROLE=SIGNAL
    std::vector<std::string> opts;    // KEY=VALUE
    double rate_hz = 0;               // --rate
};

struct Rules {
    std::string file;
    std::vector<ProtoRules> tables;  // in file order
    DecodeDefaults decode;
};

// `known_protos`: decoder ids a table may name; empty accepts any name.
Rules parseRules(const std::string& text, const std::string& file_name,
                 const std::vector<std::string>& known_protos);
// Reads and parses a rules file (InputError when unreadable).
Rules loadRules(const std::string& path, const std::vector<std::string>& known_protos);

// The keys a decoder table accepts, for error messages and the README.
const std::vector<std::string>& ruleKeys();

// The table of limits on analog lines' signal quality (`capture`/`signal` events), and
// its keys.
inline constexpr const char* kSignalTable = "signal";
const std::vector<std::string>& signalRuleKeys();

// The event type `min_frames` counts for a decoder: frame (ssi, bissc), transfer (spi),
// byte (uart), command (tmcl, tmc8100); "" (every event) for others.
std::string primaryEventType(const std::string& proto);

}  // namespace busdecode
