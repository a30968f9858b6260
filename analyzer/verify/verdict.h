#pragma once
// The result of verifying one capture, and how it is told: one line on stdout per
// capture, a summary line, and the JUnit XML file (one testsuite, one testcase per
// capture and rule; a capture that could not be read is one testcase with an <error>).
#include <string>
#include <vector>

#include "rule_checker.h"
#include "sinks/xml_escape.h"

namespace busdecode {

struct CaptureVerdict {
    std::string capture;
    bool input_error = false;  // unreadable capture, unbound role...: exit 2
    std::string error;
    std::vector<RuleOutcome> outcomes;
    std::string events;              // "bissc 1000 frames"
    double seconds = 0;              // decode time
    std::vector<std::string> hints;  // the decoders' advice (CaptureFacts::advice)
    bool passed() const;
};

// "PASS cap.vcd  (bissc 1000 frames; 7 rules)" / "FAIL cap.vcd  bissc.max_crc_errors: ...; ..."
// / "ERROR cap.vcd  <message>".
std::string verdictLine(const CaptureVerdict& v);
// "3 captures: 2 passed, 1 failed, 0 unreadable; 21 rule checks, 1 failed".
std::string summaryLine(const std::vector<CaptureVerdict>& all);
struct BatchCounts {
    std::size_t captures = 0, passed = 0, failed = 0, unreadable = 0, checks = 0, failed_checks = 0;
};
std::string summaryLine(const BatchCounts& counts);
// JUnit XML in the common schema (testsuites > testsuite with properties, testcases,
// system-out, system-err; a testcase holds at most one failure or error). `shard` ("K/N",
// or "" for a whole run) becomes a property for `decode merge-junit`.
// `checks` (VerifyPlan::checks) becomes a property too, "" none.
std::string junitXml(const std::vector<CaptureVerdict>& all, const std::string& rules_file,
                     const std::string& shard = "", const std::string& checks = "");
// The pieces junitXml is made of, shared with merge-junit.
struct JunitSuiteHead {
    std::size_t tests = 0, failures = 0, errors = 0;
    double seconds = 0;
    std::string rules_file, shard, checks;
};
std::string junitOpening(const JunitSuiteHead& head);
struct JunitCase {
    std::string name, classname, time;
    std::string outcome;  // "", "failure" or "error"
    std::string message, type, text;
};
std::string junitCaseXml(const JunitCase& c);  // up to and with <properties>
std::string junitClosing(const std::string& out, const std::string& err);
// Character data: keeps line breaks (attributes, xmlEscape, encode them).
std::string xmlText(const std::string& s);
// Escapes text for XML attributes and character data; drops characters XML 1.0 forbids.
// The JUnit classname of each capture, in order: "busdecode.<stem>" with every character
// but letters, digits, '_' and '-' made '_' (CI tools split a classname at its last dot
// into package and class: no ".vcd"); captures of the same stem in different folders
// take their folders into the name, and a name still taken gets "_2", "_3"...
std::vector<std::string> junitClassNames(const std::vector<CaptureVerdict>& all);
// The same for capture paths in the order a run verifies them.
std::vector<std::string> junitClassNames(const std::vector<std::string>& captures);

}  // namespace busdecode
