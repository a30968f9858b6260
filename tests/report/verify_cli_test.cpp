// `decode verify` end to end on generated captures: a clean capture passes, each kind of
// fault fails the right rule at the time of its first faulty frame, JUnit is well-formed
// with the right counts, --jobs 2 (and --threads 1) prints exactly what --jobs 1 prints,
// bad input exits 2.
#include <gtest/gtest.h>

#include <QString>
#include <QXmlStreamReader>
#include <cmath>
#include <filesystem>
#include <regex>
#include <sstream>

#include "fault_captures.h"
#include "support/paths.h"

namespace busdecode {
namespace {

using test::FaultCapture;

std::string dir() {
    return test::tempDir() + "/verify";
}

std::vector<FaultCapture> capturesOf(const std::string& proto) {
    std::vector<FaultCapture> out;
    for (const auto& c : test::faultCaptures(dir()))
        if (c.proto == proto) out.push_back(c);
    return out;
}

std::string rulesFile(const std::string& name, const char* text) {
    std::filesystem::create_directories(dir());
    const std::string path = dir() + "/" + name;
    test::writeFile(path, text);
    return path;
}

double toNs(double v, const std::string& unit) {
    if (unit == "s") return v * 1e9;
    if (unit == "ms") return v * 1e6;
    if (unit == "us") return v * 1e3;
    return v;
}

// The time a failed rule names: "first at X" (limit 0) or "limit passed at X".
double failTime(const std::string& line, const std::string& rule) {
    auto p = line.find(rule + ":");
    if (p == std::string::npos) return NAN;
    std::string rest = line.substr(p);
    rest = rest.substr(0, rest.find("; "));
    std::smatch m;
    const std::regex passed("limit passed at ([0-9.]+) (s|ms|us|ns)");
    const std::regex first("first at ([0-9.]+) (s|ms|us|ns)");
    if (std::regex_search(rest, m, passed) || std::regex_search(rest, m, first))
        return toNs(std::stod(m[1]), m[2]);
    return NAN;
}

std::vector<std::string> verifyArgs(const std::vector<FaultCapture>& caps,
                                    const std::string& rules) {
    std::vector<std::string> a{"verify"};
    for (const auto& c : caps)
        a.push_back(c.path);
    a.push_back("--rules");
    a.push_back(rules);
    return a;
}

void expectRightRulesFail(const std::vector<FaultCapture>& caps, const std::string& rules) {
    const auto r = test::runDecode(verifyArgs(caps, rules));
    EXPECT_EQ(r.status, 1) << r.out << r.err;
    const auto out = test::splitLines(r.out);
    ASSERT_EQ(out.size(), caps.size() + 1) << r.out << r.err;
    for (std::size_t i = 0; i < caps.size(); ++i) {
        const auto& c = caps[i];
        const std::string& l = out[i];
        SCOPED_TRACE(l);
        EXPECT_NE(l.find(c.path), std::string::npos);
        if (c.failing_rule.empty()) {
            EXPECT_EQ(l.rfind("PASS", 0), 0u);
            continue;
        }
        EXPECT_EQ(l.rfind("FAIL", 0), 0u);
        // The right rule, and no other.
        std::smatch m;
        std::string rest = l;
        const std::regex failed("(" + c.proto + "\\.[a-z_]+): ");
        int rules_failed = 0;
        while (std::regex_search(rest, m, failed)) {
            EXPECT_EQ(m[1], c.failing_rule);
            ++rules_failed;
            rest = m.suffix();
        }
        EXPECT_EQ(rules_failed, 1);
        const double t = failTime(l, c.failing_rule);
        ASSERT_FALSE(std::isnan(t)) << "no time for " << c.failing_rule;
        // Within a few bit times of the faulty frame's first edge (frames are > 40 us apart).
        EXPECT_NEAR(t, c.first_ns, 5000) << c.failing_rule;
    }
}

TEST(VerifyCli, BisscCleanPassesAndEachFaultFailsItsRuleAtItsTime) {
    expectRightRulesFail(capturesOf("bissc"), rulesFile("bissc.toml", test::kBisscRules));
}

TEST(VerifyCli, SsiCleanPassesAndEachFaultFailsItsRuleAtItsTime) {
    expectRightRulesFail(capturesOf("ssi"), rulesFile("ssi.toml", test::kSsiRules));
}

TEST(VerifyCli, AllCleanExitsZero) {
    const auto caps = capturesOf("bissc");
    const auto r = test::runDecode(
        {"verify", caps[0].path, "--rules", rulesFile("bissc.toml", test::kBisscRules)});
    EXPECT_EQ(r.status, 0) << r.out << r.err;
    EXPECT_NE(r.out.find("1 capture: 1 passed, 0 failed, 0 unreadable; 9 rule checks, 0 failed"),
              std::string::npos)
        << r.out;
}

TEST(VerifyCli, HintsGoToStderrAndJunitNotBetweenTheVerdictLines) {
    // A width that does not fit: every frame fails, and the hint says what to check.
    const auto caps = capturesOf("bissc");
    const std::string junit = dir() + "/hint.xml";
    const auto r = test::runDecode({"verify", caps[0].path, "--rules",
                                    rulesFile("bissc.toml", test::kBisscRules), "--opt", "bits=20",
                                    "--junit", junit});
    EXPECT_EQ(r.status, 1) << r.out << r.err;
    EXPECT_EQ(test::splitLines(r.out).size(), 2u) << r.out;  // the verdict and the summary
    const std::string hint = "decode: " + caps[0].path + ": hint: bissc: none of the ";
    EXPECT_EQ(r.err.rfind(hint, 0), 0u) << r.err;
    EXPECT_NE(r.err.find(" answered frames came out clean (CRC right, stop bit low) with bits=20"),
              std::string::npos)
        << r.err;
    EXPECT_EQ(test::splitLines(r.err).size(), 1u) << r.err;
    EXPECT_NE(test::readFile(junit).find("<system-err>" + r.err), std::string::npos);

    const auto clean = test::runDecode(
        {"verify", caps[0].path, "--rules", rulesFile("bissc.toml", test::kBisscRules)});
    EXPECT_EQ(clean.err, "");
}

struct JunitCounts {
    int suites = 0, cases = 0, failures = 0, errors = 0;
    int tests_attr = -1, failures_attr = -1, errors_attr = -1;
    std::string error;
    std::string stripped;  // the XML without times, timestamp and host
};

JunitCounts readJunit(const std::string& xml) {
    JunitCounts c;
    QXmlStreamReader r(QString::fromStdString(xml));
    while (!r.atEnd()) {
        r.readNext();
        if (!r.isStartElement()) continue;
        const QString n = r.name().toString();
        if (n == "testsuite") {
            ++c.suites;
            c.tests_attr = r.attributes().value(QString("tests")).toInt();
            c.failures_attr = r.attributes().value(QString("failures")).toInt();
            c.errors_attr = r.attributes().value(QString("errors")).toInt();
        }
        if (n == "testcase") ++c.cases;
        if (n == "failure") ++c.failures;
        if (n == "error") ++c.errors;
    }
    if (r.hasError()) c.error = r.errorString().toStdString();
    c.stripped = std::regex_replace(xml, std::regex(" (time|timestamp|hostname)=\"[^\"]*\""), "");
    return c;
}

TEST(VerifyCli, JunitIsWellFormedWithTheRightCountsAndJobsOrThreadsDoNotChangeResults) {
    auto caps = capturesOf("bissc");
    const std::string rules = rulesFile("bissc.toml", test::kBisscRules);
    auto args = verifyArgs(caps, rules);
    args.push_back("--junit");
    auto one = args, two = args, single = args;
    one.insert(one.end(), {dir() + "/j1.xml", "--jobs", "1"});
    two.insert(two.end(), {dir() + "/j2.xml", "--jobs", "2"});
    // Two captures at once, each read and decoded on one thread.
    single.insert(single.end(), {dir() + "/j3.xml", "--jobs", "2", "--threads", "1"});
    const auto r1 = test::runDecode(one);
    const auto r2 = test::runDecode(two);
    const auto r3 = test::runDecode(single);
    EXPECT_EQ(r1.status, 1) << r1.err;
    EXPECT_EQ(r2.status, 1) << r2.err;
    EXPECT_EQ(r3.status, 1) << r3.err;
    EXPECT_EQ(r1.out, r2.out);
    EXPECT_EQ(r1.out, r3.out);
    const auto j1 = readJunit(test::readFile(dir() + "/j1.xml"));
    const auto j2 = readJunit(test::readFile(dir() + "/j2.xml"));
    ASSERT_EQ(j1.error, "");
    EXPECT_EQ(j1.suites, 1);
    EXPECT_EQ(j1.cases, int(caps.size()) * 9);  // 9 rules per capture
    EXPECT_EQ(j1.tests_attr, j1.cases);
    // Every faulty capture fails its one rule.
    int expected_failures = 0;
    for (const auto& c : caps)
        expected_failures += c.failing_rule.empty() ? 0 : 1;
    EXPECT_EQ(j1.failures, expected_failures) << r1.out;
    EXPECT_EQ(j1.failures_attr, j1.failures);
    EXPECT_EQ(j1.errors, 0);
    EXPECT_EQ(j1.stripped, j2.stripped);
    EXPECT_EQ(j1.stripped, readJunit(test::readFile(dir() + "/j3.xml")).stripped);
}

TEST(VerifyCli, LimitAboveZeroFailsAtTheEventThatPassedIt) {
    for (const auto& c : capturesOf("bissc")) {
        if (c.failing_rule != "bissc.max_crc_errors") continue;
        const auto r = test::runDecode(
            {"verify", c.path, "--rules", rulesFile("faults.toml", "[bissc]\nmax_faults = 1\n")});
        EXPECT_EQ(r.status, 1);
        EXPECT_NE(r.out.find("bissc.max_faults: 2 events with errors (limit 1)"), std::string::npos)
            << r.out;
        EXPECT_NEAR(failTime(r.out, "bissc.max_faults"), c.second_ns, 5000) << r.out;
        return;
    }
    FAIL() << "no CRC capture";
}

TEST(VerifyCli, ExpectedRegisterValues) {
    const auto& reg = test::registerCapture(dir());
    ASSERT_EQ(reg.first_ns.size(), 2u);
    const auto good =
        test::runDecode({"verify", reg.path, "--rules",
                         rulesFile("reg_good.toml",
                                   "[bissc]\nregisters = { \"0x7E\" = 0x69, \"0x7F\" = 0x43 }\n")});
    EXPECT_EQ(good.status, 0) << good.out << good.err;
    const auto bad = test::runDecode(
        {"verify", reg.path, "--rules",
         rulesFile("reg_bad.toml",
                   "[bissc]\nregisters = { \"0x7E\" = 0x69, \"0x7F\" = 0x44, \"0x10\" = 1 }\n")});
    EXPECT_EQ(bad.status, 1);
    EXPECT_EQ(bad.out.find("bissc.registers.0x7E"), std::string::npos) << bad.out;  // passed
    EXPECT_NE(bad.out.find("bissc.registers.0x7F: 1 of 1 access with data other than 0x44"),
              std::string::npos)
        << bad.out;
    EXPECT_NEAR(failTime(bad.out, "bissc.registers.0x7F"), reg.first_ns[1], 5000) << bad.out;
    EXPECT_NE(bad.out.find("bissc.registers.0x10: register 0x10 never accessed"),
              std::string::npos);
}

TEST(VerifyCli, UnreadableCaptureIsAnErrorExitTwo) {
    const auto caps = capturesOf("bissc");
    const std::string rules = rulesFile("bissc.toml", test::kBisscRules);
    const auto r = test::runDecode({"verify", caps[0].path, dir() + "/missing.vcd", "--rules",
                                    rules, "--junit", dir() + "/err.xml"});
    EXPECT_EQ(r.status, 2) << r.out << r.err;
    EXPECT_NE(r.out.find("ERROR " + dir() + "/missing.vcd"), std::string::npos) << r.out;
    // One line on stderr, naming the file once.
    EXPECT_EQ(r.err, "decode verify: " + dir() +
                         "/missing.vcd: cannot open: No such file or "
                         "directory\n");
    const auto j = readJunit(test::readFile(dir() + "/err.xml"));
    EXPECT_EQ(j.error, "");
    EXPECT_EQ(j.errors, 1);
    EXPECT_EQ(j.errors_attr, 1);
}

TEST(VerifyCli, UnwritableOutputsFailBeforeAnyCaptureIsDecoded) {
    // A JUnit or report path in a directory that does not exist is found out at once,
    // not after a long batch: nothing is decoded, nothing is left behind.
    const auto caps = capturesOf("bissc");
    const std::string rules = rulesFile("bissc.toml", test::kBisscRules);
    const std::string nowhere = dir() + "/no/such/dir";
    auto r =
        test::runDecode({"verify", caps[0].path, "--rules", rules, "--junit", nowhere + "/j.xml"});
    EXPECT_EQ(r.status, 2);
    EXPECT_EQ(r.out, "");
    EXPECT_EQ(r.err, "decode verify: " + nowhere +
                         "/j.xml: cannot write: No such file or "
                         "directory\n");
    r = test::runDecode({caps[0].path, "--proto", "bissc", "--report", nowhere + "/r.html"});
    EXPECT_EQ(r.status, 2);
    EXPECT_EQ(r.out, "");
    EXPECT_EQ(r.err, "decode: " + nowhere + "/r.html: cannot write: No such file or directory\n");
    // A writable path keeps no probe file behind.
    r = test::runDecode({caps[0].path, "--proto", "bissc", "--report", dir() + "/probe.txt"});
    EXPECT_EQ(r.status, 0) << r.err;
    for (const auto& entry : std::filesystem::directory_iterator(dir()))
        EXPECT_EQ(entry.path().filename().string().find(".tmp-"), std::string::npos)
            << entry.path();
}

TEST(VerifyCli, BadRulesExitTwoWithFileLineAndKey) {
    const auto caps = capturesOf("bissc");
    const std::string rules =
        rulesFile("bad.toml", "[bissc]\nmin_frames = 1\nmax_line_delay = 5\n");
    const auto r = test::runDecode({"verify", caps[0].path, "--rules", rules});
    EXPECT_EQ(r.status, 2);
    EXPECT_NE(r.err.find(rules + ":3: [bissc] max_line_delay: unknown key"), std::string::npos)
        << r.err;
    EXPECT_EQ(r.out, "");
}

TEST(VerifyCli, DecodeTableInTheRulesPicksTheDecoderAndOptions) {
    const auto caps = capturesOf("ssi");
    // Without --proto, [decode] (or else the rule tables) picks the decoder; its options
    // are checked like --opt.
    const std::string good =
        rulesFile("ssi_decode.toml",
                  "[ssi]\nmin_frames = 30\n[decode]\nproto = \"ssi\"\nopt = { bits = 25 }\n");
    EXPECT_EQ(test::runDecode({"verify", caps[0].path, "--rules", good}).status, 0);
    const std::string bad =
        rulesFile("ssi_bad_opt.toml", "[ssi]\nmin_frames = 30\n[decode]\nopt = { bitz = 25 }\n");
    const auto r = test::runDecode({"verify", caps[0].path, "--rules", bad});
    EXPECT_EQ(r.status, 2);
    EXPECT_NE(r.err.find("bitz"), std::string::npos) << r.err;
}

TEST(VerifyCli, AnOptionOnTheCommandLineReplacesTheRulesOneScopedOrNot) {
    const auto caps = capturesOf("ssi");
    const std::string rules = rulesFile(
        "ssi_scoped.toml",
        "[ssi]\nmin_frames = 30\n[decode]\nproto = \"ssi\"\nopt = { \"ssi.bits\" = 7 }\n");
    // 7 bits cannot hold the fields: the rules' option alone is refused.
    EXPECT_EQ(test::runDecode({"verify", caps[0].path, "--rules", rules}).status, 2);
    const auto r = test::runDecode({"verify", caps[0].path, "--rules", rules, "--opt", "bits=25"});
    EXPECT_EQ(r.status, 0) << r.err;
}

TEST(VerifyCli, BadOptionValueIsOneUsageLineNotAnErrorPerCapture) {
    const auto caps = capturesOf("bissc");
    const std::string rules = rulesFile("bissc.toml", test::kBisscRules);
    auto args = verifyArgs(caps, rules);
    args.insert(args.end(), {"--opt", "crc_poly=zz"});
    const auto r = test::runDecode(args);
    EXPECT_EQ(r.status, 2);
    EXPECT_EQ(r.out, "");
    EXPECT_EQ(r.err,
              "decode verify: decoder bissc: option crc_poly=zz: expected an integer from 2 to "
              "4294967295\n");
}

TEST(VerifyCli, RulesForADecoderNotRunAreAnErrorNotAPass) {
    const auto caps = capturesOf("bissc");
    const std::string rules = rulesFile("ssi_only.toml", "[ssi]\nmax_faults = 0\n");
    const auto r = test::runDecode({"verify", caps[0].path, "--rules", rules, "--proto", "bissc"});
    EXPECT_EQ(r.status, 2) << r.out;
    EXPECT_EQ(r.out, "");
    EXPECT_EQ(r.err, "decode verify: " + rules +
                         ":1: [ssi]: no such decoder in this run (decoding with bissc): give "
                         "--proto ssi or remove the table\n");
}

TEST(VerifyCli, AnEmptyListOrAnEmptyShardArgumentIsAnErrorInEveryShard) {
    const auto caps = capturesOf("bissc");
    const std::string rules = rulesFile("bissc.toml", test::kBisscRules);
    const std::string list = dir() + "/empty-list.txt";
    test::writeFile(list, "");
    for (const char* shard : {"1/2", "2/2"}) {
        const auto r =
            test::runDecode({"verify", "--from-list", list, "--rules", rules, "--shard", shard});
        EXPECT_EQ(r.status, 2) << shard;
        EXPECT_EQ(r.err, "decode verify: " + list + ": the list names no capture\n");
    }
    const auto r = test::runDecode({"verify", caps[0].path, "--rules", rules, "--shard", ""});
    EXPECT_EQ(r.status, 2);
    EXPECT_EQ(r.out, "");
    EXPECT_EQ(r.err, "decode: --shard: expected K/N (e.g. 2/8), got nothing\n");
    const auto none = test::runDecode({"verify", "--rules", rules});
    EXPECT_EQ(none.status, 2);
    EXPECT_EQ(test::splitLines(none.err).size(), 1u) << none.err;
}

}  // namespace
}  // namespace busdecode
