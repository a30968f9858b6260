// JUnit XML parsed back with QXmlStreamReader: well-formed, one testsuite, one testcase
// per capture and rule, failures and errors counted right; and the verdict lines.
#include <gtest/gtest.h>

#include <QString>
#include <QXmlStreamReader>

#include <filesystem>

#include "core/utf8.h"
#include "support/paths.h"
#include "verify/verdict.h"

namespace busdecode {
namespace {

RuleOutcome outcome(const std::string& proto, const std::string& rule, bool passed,
                    std::string msg) {
    RuleOutcome o;
    o.proto = proto;
    o.rule = rule;
    o.passed = passed;
    o.message = std::move(msg);
    return o;
}

std::vector<CaptureVerdict> sampleVerdicts() {
    CaptureVerdict clean;
    clean.capture = "caps/clean.vcd";
    clean.outcomes = {
        outcome("bissc", "max_crc_errors", true, "0 events with CRC errors (limit 0)"),
        outcome("bissc", "min_frames", true, "100 frames (minimum 10)")};
    clean.events = "bissc 100 frames";
    CaptureVerdict bad;
    bad.capture = "caps/crc & <odd> \"name\".vcd";
    bad.outcomes = {
        outcome("bissc", "max_crc_errors", false,
                "2 events with CRC errors (limit 0), first at 1.000 ms"),
        outcome("bissc", "min_frames", true, "100 frames (minimum 10)"),
        outcome("bissc", "clock_hz", false, "1 of 100 values outside [1 MHz, 2 MHz]\x01")};
    CaptureVerdict broken;
    broken.capture = "caps/missing.vcd";
    broken.input_error = true;
    broken.error = "caps/missing.vcd: cannot open";
    return {clean, bad, broken};
}

struct Parsed {
    int suites = 0, cases = 0, failures = 0, errors = 0;
    int attr_tests = -1, attr_failures = -1, attr_errors = -1;
    std::vector<std::string> names;
    std::vector<std::string> failure_messages;
    std::string error;
};

Parsed parse(const std::string& xml) {
    Parsed p;
    QXmlStreamReader r(QString::fromStdString(xml));
    while (!r.atEnd()) {
        r.readNext();
        if (!r.isStartElement()) continue;
        const auto name = r.name().toString();
        const auto attr = [&](const char* a) {
            return r.attributes().value(QString(a)).toString();
        };
        if (name == "testsuite") {
            ++p.suites;
            p.attr_tests = attr("tests").toInt();
            p.attr_failures = attr("failures").toInt();
            p.attr_errors = attr("errors").toInt();
        } else if (name == "testcase") {
            ++p.cases;
            p.names.push_back((attr("classname") + " " + attr("name")).toStdString());
        } else if (name == "failure") {
            ++p.failures;
            p.failure_messages.push_back(attr("message").toStdString());
        } else if (name == "error") {
            ++p.errors;
        }
    }
    if (r.hasError()) p.error = r.errorString().toStdString();
    return p;
}

TEST(Junit, WellFormedWithTheRightCounts) {
    const std::string xml = junitXml(sampleVerdicts(), "rules.toml");
    const Parsed p = parse(xml);
    ASSERT_EQ(p.error, "") << xml;
    EXPECT_EQ(p.suites, 1);
    EXPECT_EQ(p.cases, 6);  // 2 + 3 rules, 1 unreadable capture
    EXPECT_EQ(p.failures, 2);
    EXPECT_EQ(p.errors, 1);
    EXPECT_EQ(p.attr_tests, 6);
    EXPECT_EQ(p.attr_failures, 2);
    EXPECT_EQ(p.attr_errors, 1);
    EXPECT_EQ(p.names[0], "busdecode.clean bissc.max_crc_errors");
    EXPECT_EQ(p.names[2], "busdecode.crc____odd___name_ bissc.max_crc_errors");
    EXPECT_EQ(p.names[5], "busdecode.missing decode");
    EXPECT_EQ(p.failure_messages[0], "2 events with CRC errors (limit 0), first at 1.000 ms");
    EXPECT_EQ(p.failure_messages[1],
              "1 of 100 values outside [1 MHz, 2 MHz]");  // control char dropped
}

// Validates against the Ant JUnit schema (tests/report/junit_ant.xsd) with xmllint.
TEST(Junit, ValidatesAgainstTheAntJunitSchema) {
    if (!std::filesystem::exists("/usr/bin/xmllint"))
        GTEST_SKIP() << "xmllint is not installed (Debian package libxml2-utils)";
    const std::string xsd = test::sourceDir() + "/tests/report/junit_ant.xsd";
    auto validate = [&](const std::string& name, const std::string& xml) {
        const std::string path = test::tempDir() + "/" + name;
        test::writeFile(path, xml);
        return test::runCommand("xmllint --noout --schema " + test::shellQuote(xsd) + " " +
                                test::shellQuote(path));
    };
    const auto good = validate("junit.xml", junitXml(sampleVerdicts(), "rules.toml"));
    EXPECT_EQ(good.status, 0) << good.err;
    EXPECT_EQ(validate("empty.xml", junitXml({}, "rules.toml")).status, 0);
    // The schema does bite: a testcase with two failures is rejected.
    std::string bad = junitXml(sampleVerdicts(), "rules.toml");
    const auto at = bad.find("<failure");
    bad.insert(at, "<failure type=\"x\"/>");
    EXPECT_NE(validate("bad.xml", bad).status, 0);
}

// Jenkins splits a classname at its last dot: "busdecode" is the package, the capture's
// stem the class, whatever dots or folders the file name has; same stems stay apart.
TEST(Junit, ClassNamesAreThePackageAndTheCaptureStem) {
    auto named = [](std::vector<std::string> files) {
        std::vector<CaptureVerdict> all;
        for (auto& f : files) {
            CaptureVerdict v;
            v.capture = std::move(f);
            all.push_back(v);
        }
        return junitClassNames(all);
    };
    EXPECT_EQ(named({"/data/run.2024-03.vcd", "enc.sr"}),
              (std::vector<std::string>{"busdecode.run_2024-03", "busdecode.enc"}));
    EXPECT_EQ(named({"a/enc.vcd", "b/enc.vcd", "../c/x.vcd"}),
              (std::vector<std::string>{"busdecode.a_enc", "busdecode.b_enc", "busdecode.x"}));
    EXPECT_EQ(named({"enc.vcd", "enc.sr", "enc.csv"}),
              (std::vector<std::string>{"busdecode.enc", "busdecode.enc_2", "busdecode.enc_3"}));
    for (const auto& name : named({"/tmp/a b/x.y.z.vcd"}))
        EXPECT_EQ(name.rfind('.'), std::string("busdecode").size()) << name;
}

TEST(Junit, EmptyBatchIsStillWellFormed) {
    const Parsed p = parse(junitXml({}, "r.toml"));
    EXPECT_EQ(p.error, "");
    EXPECT_EQ(p.suites, 1);
    EXPECT_EQ(p.cases, 0);
}

TEST(Junit, BytesThatAreNotUtf8AreReplacedEverywhere) {
    // A Latin-1 file name (caf\xe9.vcd) lands in attributes, in the failure text and in
    // system-out; each place must stay UTF-8 or the file is not XML.
    std::vector<CaptureVerdict> all = sampleVerdicts();
    all[1].capture = "caps/caf\xE9.vcd";
    all[2].capture = "caps/gone\xFF.vcd";
    all[2].error = "caps/gone\xFF.vcd: cannot open";
    const std::string xml = junitXml(all, "r\xE9.toml");
    for (std::size_t i = 0; i < xml.size(); ++i) {
        if (static_cast<unsigned char>(xml[i]) < 0x80) continue;
        const std::size_t n = utf8SequenceLength(xml, i);
        ASSERT_NE(n, 0u) << "byte " << i << " of\n" << xml;
        i += n - 1;
    }
    EXPECT_NE(xml.find("caf\xEF\xBF\xBD.vcd"), std::string::npos) << xml;
    EXPECT_EQ(parse(xml).error, "");
}

TEST(VerdictLines, PassFailErrorAndSummary) {
    const auto v = sampleVerdicts();
    EXPECT_EQ(verdictLine(v[0]), "PASS  caps/clean.vcd  (bissc 100 frames; 2 rules)");
    const std::string fail = verdictLine(v[1]);
    EXPECT_EQ(fail.rfind("FAIL  caps/crc", 0), 0u);
    EXPECT_NE(fail.find("bissc.max_crc_errors: 2 events with CRC errors (limit 0), first at 1.000 "
                        "ms; bissc.clock_hz:"),
              std::string::npos)
        << fail;
    EXPECT_EQ(fail.find("min_frames"), std::string::npos);
    EXPECT_EQ(verdictLine(v[2]), "ERROR caps/missing.vcd  caps/missing.vcd: cannot open");
    EXPECT_EQ(summaryLine(v),
              "3 captures: 1 passed, 1 failed, 1 unreadable; 5 rule checks, 2 failed");
}

}  // namespace
}  // namespace busdecode
