// What the capture layer finds in scope captures, end to end through `decode`: a pair
// fault as an event of its own and on the decoded events it overlaps, each analog line's
// `signal` event against the generated truth, and `verify`'s [signal] rules failing slow
// edges and a low swing.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <regex>
#include <sstream>

#include <fmt/format.h>

#include "capture/scope_csv_writer.h"
#include "core/waveform.h"
#include "support/paths.h"

namespace busdecode::test {
namespace {

constexpr double kBaud = 115200;
constexpr double kBitNs = 1e9 / kBaud;
const std::string kText = "RS-422 with one wire open";

// 8N1 characters on line TX from 20 us on, 3 us apart; returns the time after the last.
Waveform uartText(const std::string& text, double gap_ns = 3'000) {
    WaveBuilder b(Timebase{1, 1'000'000'000}, {"TX"}, {1});
    double t = 20'000;
    for (const char c : text) {
        b.setNs(0, t, false);
        for (int i = 0; i < 8; ++i)
            b.setNs(0, t + (1 + i) * kBitNs, (std::uint8_t(c) >> i) & 1);
        b.setNs(0, t + 9 * kBitNs, true);
        t += 10 * kBitNs + gap_ns;
    }
    return b.build(b.ticksFromNs(t + 50'000));
}

AnalogStyle scope(double rise_ns) {
    AnalogStyle s;
    s.sample_ns = 200;
    s.low_v = 0;
    s.high_v = 3.3;
    s.rise_ns = rise_ns;
    s.snr_db = 30;
    return s;
}

std::vector<std::string> linesOf(const std::string& s) {
    std::vector<std::string> out;
    std::istringstream in(s);
    for (std::string l; std::getline(in, l);)
        out.push_back(l);
    return out;
}

// The number after "key": in a JSON line (NaN when absent or null).
double number(const std::string& line, const std::string& key) {
    const auto p = line.find("\"" + key + "\":");
    if (p == std::string::npos) return NAN;
    const char* at = line.c_str() + p + key.size() + 3;
    char* end = nullptr;
    const double v = std::strtod(at, &end);
    return end == at ? NAN : v;
}

std::string writeCapture(const std::string& name, const Waveform& w, const AnalogStyle& s) {
    const std::string p = tempDir() + "/" + name;
    writeScopeCsv(w, p, ScopeDialect::Rigol, s);
    return p;
}

TEST(ScopeFindings, AnOpenWireIsAPairFaultEventAndMarksTheBytesItOverlaps) {
    AnalogStyle s = scope(0.2 * kBitNs);
    s.differential = true;
    s.open_line = 0;
    // Between the 11th and 12th characters the negative wire goes open.
    const double open_ns = 20'000 + 11 * (10 * kBitNs + 3'000) - 1'500;
    s.open_after_ns = open_ns;
    const std::string p = writeCapture("rs422.csv", uartText(kText), s);
    const auto r = runDecode(
        {p, "--proto", "uart", "--map", "rx=TX+,TX-", "--opt", "baud=115200", "--format", "jsonl"});
    ASSERT_EQ(r.status, 0) << r.err;
    std::vector<std::string> bytes, faults;
    double last_start = -1;
    for (const auto& l : linesOf(r.out)) {
        EXPECT_GE(number(l, "start_ns"), last_start) << "out of time order: " << l;
        last_start = number(l, "start_ns");
        if (l.find("\"type\":\"byte\"") != std::string::npos) bytes.push_back(l);
        if (l.find("\"type\":\"pair_fault\"") != std::string::npos) faults.push_back(l);
    }
    ASSERT_EQ(bytes.size(), kText.size()) << r.out;
    // The pair's signal summary comes last, at the capture's end.
    EXPECT_NE(linesOf(r.out).back().find("\"type\":\"signal\",\"start_ns\":"), std::string::npos)
        << r.out;
    ASSERT_EQ(faults.size(), 1u) << r.out;
    const std::string& f = faults[0];
    EXPECT_NE(f.find("\"proto\":\"capture\""), std::string::npos) << f;
    EXPECT_NE(f.find("\"pair\":\"TX+,TX-\",\"wire\":\"TX-\",\"working\":\"TX+\",\"kind\":\"open\""),
              std::string::npos)
        << f;
    EXPECT_NE(f.find("\"errors\":[\"pair_fault\"]"), std::string::npos) << f;
    // From the moment it opened (or the next start bit at the latest) to the end.
    EXPECT_GE(number(f, "start_ns"), open_ns - 2 * s.sample_ns) << f;
    EXPECT_LE(number(f, "start_ns"), open_ns + 1'500 + 2 * s.sample_ns) << f;
    EXPECT_GE(number(f, "end_ns"), number(bytes.back(), "end_ns")) << f;
    // Every character decodes; those after the wire opened carry the fault.
    for (std::size_t i = 0; i < bytes.size(); ++i) {
        EXPECT_EQ(number(bytes[i], "value"), double(std::uint8_t(kText[i]))) << bytes[i];
        const bool after = number(bytes[i], "end_ns") > number(f, "start_ns");
        EXPECT_EQ(bytes[i].find("\"errors\":[\"pair_fault\"]") != std::string::npos, after)
            << bytes[i];
    }
}

TEST(ScopeFindings, SignalEventGivesTheGeneratedLevelsAndRiseTime) {
    const double rise_ns = 0.2 * kBitNs;  // 0-100 %: 10-90 % is 0.8 of it
    AnalogStyle s = scope(rise_ns);
    s.sample_ns = 20;
    s.low_v = 0.2;
    s.high_v = 4.8;
    const std::string p = writeCapture("single.csv", uartText("UU"), s);
    const auto r = runDecode(
        {p, "--proto", "uart", "--map", "rx=TX", "--opt", "baud=115200", "--format", "jsonl"});
    ASSERT_EQ(r.status, 0) << r.err;
    std::string sig;
    for (const auto& l : linesOf(r.out))
        if (l.find("\"type\":\"signal\"") != std::string::npos) sig = l;
    ASSERT_FALSE(sig.empty()) << r.out;
    EXPECT_NE(sig.find("\"line\":\"TX\""), std::string::npos) << sig;
    EXPECT_NEAR(number(sig, "low_v"), 0.2, 0.1) << sig;
    EXPECT_NEAR(number(sig, "high_v"), 4.8, 0.1) << sig;
    EXPECT_NEAR(number(sig, "swing_v"), 4.6, 0.15) << sig;
    EXPECT_NEAR(number(sig, "threshold_v"), 2.5, 0.1) << sig;
    EXPECT_NEAR(number(sig, "hysteresis_v"), 0.46, 0.02) << sig;
    EXPECT_NEAR(number(sig, "rise_median_ns"), 0.8 * rise_ns, 0.05 * rise_ns) << sig;
    EXPECT_NEAR(number(sig, "fall_median_ns"), 0.8 * rise_ns, 0.05 * rise_ns) << sig;
    EXPECT_GE(number(sig, "rise_p99_ns"), number(sig, "rise_median_ns")) << sig;
    // "UU": 0x55 between start and stop bits rises 5 times per character.
    EXPECT_EQ(number(sig, "rises"), 10) << sig;
    EXPECT_EQ(number(sig, "falls"), 10) << sig;
    EXPECT_LT(number(sig, "overshoot_pct"), 10) << sig;
    EXPECT_EQ(number(sig, "reversals"), 0) << sig;
}

TEST(ScopeFindings, ReportsHaveASignalQualityTablePerLineAndThePairFaults) {
    AnalogStyle s = scope(0.2 * kBitNs);
    s.differential = true;
    s.open_line = 0;
    s.open_after_ns = 60'000;
    const std::string p = writeCapture("report.csv", uartText("UART"), s);
    for (const char* ext : {"txt", "html"}) {
        const std::string report = tempDir() + "/report." + ext;
        const auto r = runDecode({p, "--proto", "uart", "--map", "rx=TX+,TX-", "--opt",
                                  "baud=115200", "--report", report});
        ASSERT_EQ(r.status, 0) << r.err;
        const std::string text = readFile(report);
        SCOPED_TRACE(text);
        if (std::string(ext) == "txt") {
            // Once open, the difference swings half: its main levels are about +-1.65 V.
            EXPECT_NE(text.find("Signal quality (analog lines; rise and fall 10-90 %)\n"
                                "  line    low"),
                      std::string::npos);
            EXPECT_TRUE(std::regex_search(
                text,
                std::regex(R"(\n  TX\+,TX- +-1\.[67][0-9]* V +1\.[67][0-9]* V +3\.[0-9]+ V )")));
            EXPECT_NE(text.find("  pair faults: 1\n"), std::string::npos);
            EXPECT_NE(text.find("TX+,TX-: TX- does not follow TX+ (open)"), std::string::npos);
        } else {
            EXPECT_NE(text.find("<h2>Signal quality</h2>"), std::string::npos);
            EXPECT_NE(text.find("<th>rise p99</th>"), std::string::npos);
            EXPECT_NE(text.find("<td>TX+,TX-</td>"), std::string::npos);
            EXPECT_NE(text.find("<p>Pair faults: 1</p>"), std::string::npos);
        }
    }
}

std::string rules(const std::string& name, const std::string& text) {
    const std::string path = tempDir() + "/" + name;
    writeFile(path, text);
    return path;
}

RunResult verify(const std::string& capture, const std::string& rules_file,
                 const std::string& junit) {
    return runDecode({"verify", capture, "--rules", rules_file, "--junit", junit});
}

TEST(ScopeFindings, SignalRulesFailSlowEdgesAndALowSwing) {
    const std::string r = rules("signal.toml",
                                "[decode]\nproto = \"uart\"\nmap = [\"rx=TX\"]\n"
                                "opt = { baud = 115200 }\n"
                                "[signal]\nmin_swing_v = 2.5\nmax_rise_ns = 1000\n"
                                "max_fall_ns = 1000\nmax_overshoot_pct = 20\n");
    const Waveform w = uartText("ok");
    const std::string good = writeCapture("good.csv", w, scope(500));
    const auto pass = verify(good, r, tempDir() + "/good.xml");
    EXPECT_EQ(pass.status, 0) << pass.out << pass.err;

    const std::string slow = writeCapture("slow.csv", w, scope(0.3 * kBitNs));
    const auto fail_slow = verify(slow, r, tempDir() + "/slow.xml");
    EXPECT_EQ(fail_slow.status, 1) << fail_slow.out << fail_slow.err;
    EXPECT_NE(fail_slow.out.find("signal.max_rise_ns"), std::string::npos) << fail_slow.out;
    EXPECT_NE(fail_slow.out.find("signal.max_fall_ns"), std::string::npos) << fail_slow.out;
    const std::string junit = readFile(tempDir() + "/slow.xml");
    EXPECT_NE(junit.find("failures=\"2\""), std::string::npos) << junit;

    AnalogStyle weak = scope(500);
    weak.high_v = 1.2;
    const std::string low = writeCapture("low.csv", w, weak);
    const auto fail_low = verify(low, r, tempDir() + "/low.xml");
    EXPECT_EQ(fail_low.status, 1) << fail_low.out << fail_low.err;
    EXPECT_NE(fail_low.out.find("signal.min_swing_v"), std::string::npos) << fail_low.out;
    EXPECT_EQ(fail_low.out.find("signal.max_rise_ns"), std::string::npos) << fail_low.out;
}

TEST(ScopeFindings, SignalRulesRefuseUnknownKeysNamingFileAndLine) {
    const std::string r = rules("bad.toml", "[signal]\nmin_swing_v = 1\nmax_jitter_ns = 3\n");
    const auto out =
        verify(writeCapture("any.csv", uartText("a"), scope(500)), r, tempDir() + "/bad.xml");
    EXPECT_EQ(out.status, 2);
    EXPECT_NE(out.err.find(r + ":3: [signal] max_jitter_ns: unknown key (valid: min_swing_v"),
              std::string::npos)
        << out.err;
}

}  // namespace
}  // namespace busdecode::test
