// The rules file: every documented key is read; unknown keys, wrong types, impossible
// ranges and TOML syntax errors are InputErrors naming file, line and key.
#include <gtest/gtest.h>

#include "core/options.h"
#include "verify/rules.h"

namespace busdecode {
namespace {

const std::vector<std::string> kKnown = {"bissc", "ssi", "spi", "uart"};

std::string errorOf(const std::string& text) {
    try {
        parseRules(text, "rules.toml", kKnown);
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

TEST(Rules, ReadsTheContractExample) {
    const Rules r = parseRules(R"(
[bissc]
max_crc_errors = 0          # frames and control accesses whose CRC fails
max_errors = 0              # nE active
max_warnings = 10           # nW active
clock_hz = [1.0e6, 10.0e6]  # [min, max]
max_line_delay_ns = 500
max_proc_cycles = 4
min_frames = 100
timeout_us = [12.5, 40]
position = [0, 67108863]
max_position_jump = 100
registers = { "0x7E" = 0x69, "127" = 0x43 }
[ssi]
max_repeat_mismatches = 0
tm_us = [15, 25]
clock_hz = [50e3, 2e6]
max_faults = 3
[decode]                    # optional: --proto/--map/--opt defaults for this batch
proto = ["bissc"]
opt = { "bissc.bits" = 26, glitch_ns = 5.5, bissc = { st_bits = 13 } }
map = { ma = "MA" }
)",
                               "rules.toml", kKnown);
    ASSERT_EQ(r.tables.size(), 2u);
    const ProtoRules& b = r.tables[0];
    EXPECT_EQ(b.proto, "bissc");
    EXPECT_EQ(b.line, 2);
    EXPECT_EQ(b.max_crc_errors, 0);
    EXPECT_EQ(b.max_warnings, 10);
    ASSERT_TRUE(b.clock_hz);
    EXPECT_DOUBLE_EQ(b.clock_hz->min, 1e6);
    EXPECT_DOUBLE_EQ(b.clock_hz->max, 10e6);
    EXPECT_DOUBLE_EQ(*b.max_line_delay_ns, 500);
    EXPECT_EQ(b.min_frames, 100);
    EXPECT_DOUBLE_EQ(b.timeout_us->min, 12.5);
    EXPECT_DOUBLE_EQ(*b.max_position_jump, 100);
    EXPECT_EQ(b.registers.at(0x7E), 0x69);
    EXPECT_EQ(b.registers.at(127), 0x43);
    EXPECT_EQ(b.keys.front(), "max_crc_errors");
    const ProtoRules& s = r.tables[1];
    EXPECT_EQ(s.proto, "ssi");
    EXPECT_EQ(s.max_repeat_mismatches, 0);
    EXPECT_DOUBLE_EQ(s.tm_us->min, 15);
    EXPECT_EQ(s.max_faults, 3);
    EXPECT_EQ(r.decode.protos, std::vector<std::string>{"bissc"});
    EXPECT_EQ(r.decode.opts,
              (std::vector<std::string>{"bissc.bits=26", "glitch_ns=5.5", "bissc.st_bits=13"}));
    EXPECT_EQ(r.decode.maps, std::vector<std::string>{"ma=MA"});
}

TEST(Rules, UnknownKeyNamesFileLineAndKey) {
    const std::string e = errorOf("[bissc]\nmax_crc_errors = 0\nmax_crc_error = 0\n");
    EXPECT_NE(e.find("rules.toml:3:"), std::string::npos) << e;
    EXPECT_NE(e.find("[bissc] max_crc_error: unknown key"), std::string::npos) << e;
    EXPECT_NE(e.find("max_crc_errors"), std::string::npos) << e;  // lists the valid ones
}

TEST(Rules, MessagesShowUtf8KeysAsWrittenAndHugeIntegersAsNumbers) {
    const std::string key = errorOf("[bissc]\n\"m\xC3\xA4x_crc_errors\" = 0\n");
    EXPECT_NE(key.find("[bissc] m\xC3\xA4x_crc_errors: unknown key"), std::string::npos) << key;
    const std::string big = errorOf("[bissc]\nmin_frames = 9223372036854775807\n");
    EXPECT_NE(big.find("min_frames: expected a whole number >= 0"), std::string::npos) << big;
    EXPECT_EQ(big.find("finite"), std::string::npos) << big;
}

TEST(Rules, WrongTypes) {
    EXPECT_NE(errorOf("[bissc]\n\nmin_frames = \"100\"\n")
                  .find("rules.toml:3: [bissc] min_frames: expected a number, got a string"),
              std::string::npos)
        << errorOf("[bissc]\n\nmin_frames = \"100\"\n");
    EXPECT_NE(errorOf("[ssi]\ntm_us = 20\n")
                  .find("rules.toml:2: [ssi] tm_us: expected [min, max], got an integer"),
              std::string::npos)
        << errorOf("[ssi]\ntm_us = 20\n");
    EXPECT_NE(errorOf("[ssi]\ntm_us = [1, 2, 3]\n").find("an array of 3"), std::string::npos);
    EXPECT_NE(errorOf("[bissc]\nmax_errors = 1.5\n").find("whole number"), std::string::npos);
    EXPECT_NE(errorOf("[bissc]\nmax_errors = -1\n").find("whole number"), std::string::npos);
    EXPECT_NE(errorOf("[bissc]\nregisters = 5\n").find("expected a table"), std::string::npos);
    EXPECT_NE(errorOf("[bissc]\nregisters = { abc = 1 }\n").find("register address"),
              std::string::npos);
    EXPECT_NE(errorOf("bissc = 3\n").find("rules.toml:1: bissc: expected a table"),
              std::string::npos)
        << errorOf("bissc = 3\n");
}

TEST(Rules, SignalTableTakesTheSignalKeysOnly) {
    const Rules r = parseRules(
        "[signal]\nmin_swing_v = 2.5\nmax_rise_ns = 150\nmax_fall_ns = 160\n"
        "max_overshoot_pct = 20\n",
        "rules.toml", kKnown);
    ASSERT_EQ(r.tables.size(), 1u);
    EXPECT_EQ(r.tables[0].proto, "signal");
    EXPECT_EQ(r.tables[0].min_swing_v, 2.5);
    EXPECT_EQ(r.tables[0].max_rise_ns, 150);
    EXPECT_EQ(r.tables[0].max_fall_ns, 160);
    EXPECT_EQ(r.tables[0].max_overshoot_pct, 20);
    EXPECT_NE(errorOf("[signal]\nmin_frames = 1\n")
                  .find("rules.toml:2: [signal] min_frames: unknown key (valid: min_swing_v, "
                        "max_rise_ns, max_fall_ns, max_overshoot_pct)"),
              std::string::npos);
    EXPECT_NE(errorOf("[bissc]\nmin_swing_v = 1\n").find("[bissc] min_swing_v: unknown key"),
              std::string::npos);
    EXPECT_NE(errorOf("[signal]\nmax_rise_ns = -3\n").find("must not be negative"),
              std::string::npos);
}

TEST(Rules, ImpossibleRanges) {
    const std::string e = errorOf("[bissc]\nmin_frames = 1\nclock_hz = [10e6, 1e6]\n");
    EXPECT_NE(
        e.find(
            "rules.toml:3: [bissc] clock_hz: impossible range: min 10000000 is above max 1000000"),
        std::string::npos)
        << e;
    EXPECT_NE(errorOf("[ssi]\ntm_us = [-5, 20]\n").find("negative"), std::string::npos);
    EXPECT_NE(errorOf("[bissc]\nclock_hz = [0, 0]\n").find("above 0 Hz"), std::string::npos);
    EXPECT_NE(errorOf("[bissc]\nmax_line_delay_ns = -1\n").find("must not be negative"),
              std::string::npos);
    EXPECT_NE(errorOf("[bissc]\nposition = [10, 5]\n").find("impossible range"), std::string::npos);
    // A negative position range is fine (signed encoders).
    EXPECT_EQ(errorOf("[bissc]\nposition = [-10, 5]\n"), "");
}

TEST(Rules, UnknownDecoderTableAndDecodeKeys) {
    EXPECT_NE(errorOf("[bisc]\nmin_frames = 1\n")
                  .find("rules.toml:1: [bisc]: unknown decoder (known: bissc, ssi"),
              std::string::npos)
        << errorOf("[bisc]\nmin_frames = 1\n");
    EXPECT_NE(errorOf("[bissc]\nmin_frames = 1\n[decode]\nprotos = [\"bissc\"]\n")
                  .find("rules.toml:4: [decode] protos: unknown key"),
              std::string::npos);
    EXPECT_NE(errorOf("[bissc]\nmin_frames = 1\n[decode]\nproto = 3\n")
                  .find("expected a string or an array"),
              std::string::npos);
    EXPECT_NE(errorOf("[decode]\nproto = \"bissc\"\n").find("no rules"), std::string::npos);
}

TEST(Rules, SyntaxErrorsCarryTheirLine) {
    const std::string e = errorOf("[bissc]\nmin_frames = 1\nmax_errors = = 0\n");
    EXPECT_EQ(e.rfind("rules.toml:3:", 0), 0u) << e;
    const std::string dup = errorOf("[bissc]\nmin_frames = 1\nmin_frames = 2\n");
    EXPECT_EQ(dup.rfind("rules.toml:3:", 0), 0u) << dup;
}

TEST(Rules, MissingFileIsAnInputError) {
    EXPECT_THROW(loadRules("/nonexistent/rules.toml", kKnown), InputError);
}

TEST(Rules, DecodeTableAcceptsArraysOfAssignments) {
    const Rules r = parseRules(
        "[ssi]\nmin_frames = 1\n[decode]\nproto = \"ssi\"\nmap = [\"clk=ENC_CLK\"]\nopt = "
        "[\"bits=13\"]\nrate = 1e6\n",
        "r.toml", {});
    EXPECT_EQ(r.decode.protos, std::vector<std::string>{"ssi"});
    EXPECT_EQ(r.decode.maps, std::vector<std::string>{"clk=ENC_CLK"});
    EXPECT_EQ(r.decode.opts, std::vector<std::string>{"bits=13"});
    EXPECT_DOUBLE_EQ(r.decode.rate_hz, 1e6);
}

}  // namespace
}  // namespace busdecode
