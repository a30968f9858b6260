#include "verdict.h"

#include <cctype>
#include <ctime>
#include <filesystem>
#include <map>
#include <set>

#include <unistd.h>

#include <fmt/format.h>

#include "app/decode_args.h"
#include "core/utf8.h"

namespace busdecode {

bool CaptureVerdict::passed() const {
    if (input_error) return false;
    for (const auto& o : outcomes)
        if (!o.passed) return false;
    return true;
}

std::string verdictLine(const CaptureVerdict& v) {
    if (v.input_error) return fmt::format("ERROR {}  {}", v.capture, v.error);
    if (v.passed())
        return fmt::format("PASS  {}  ({}; {} rules)", v.capture,
                           v.events.empty() ? "no events" : v.events, v.outcomes.size());
    std::string why;
    for (const auto& o : v.outcomes) {
        if (o.passed) continue;
        why += fmt::format("{}{}: {}", why.empty() ? "" : "; ", o.name(), o.message);
    }
    return fmt::format("FAIL  {}  {}", v.capture, why);
}

std::string summaryLine(const std::vector<CaptureVerdict>& all) {
    BatchCounts c;
    c.captures = all.size();
    for (const auto& v : all) {
        if (v.input_error)
            ++c.unreadable;
        else if (v.passed())
            ++c.passed;
        else
            ++c.failed;
        for (const auto& o : v.outcomes) {
            ++c.checks;
            if (!o.passed) ++c.failed_checks;
        }
    }
    return summaryLine(c);
}

std::string summaryLine(const BatchCounts& c) {
    return fmt::format(
        "{} capture{}: {} passed, {} failed, {} unreadable; {} rule checks, {} failed", c.captures,
        c.captures == 1 ? "" : "s", c.passed, c.failed, c.unreadable, c.checks, c.failed_checks);
}

namespace {

std::string identifier(const std::string& s) {
    std::string out;
    for (unsigned char c : s)
        out += std::isalnum(c) || c == '_' || c == '-' ? char(c) : '_';
    return out.empty() ? "_" : out;
}

// "a/b/c.vcd" -> "a_b_c" (the folders only when `folders`).
std::string captureName(const std::string& capture, bool folders) {
    const std::filesystem::path p(capture);
    std::filesystem::path named = folders ? p.parent_path() / p.stem() : p.stem();
    std::string s = named.relative_path().string();
    while (s.rfind("../", 0) == 0)
        s.erase(0, 3);
    return identifier(s);
}

}  // namespace

std::vector<std::string> junitClassNames(const std::vector<CaptureVerdict>& all) {
    std::vector<std::string> captures;
    for (const auto& v : all)
        captures.push_back(v.capture);
    return junitClassNames(captures);
}

std::vector<std::string> junitClassNames(const std::vector<std::string>& captures) {
    std::map<std::string, int> stems;
    for (const auto& c : captures)
        ++stems[captureName(c, false)];
    std::vector<std::string> out;
    std::set<std::string> taken;
    for (const auto& c : captures) {
        const std::string stem = captureName(c, false);
        std::string name = "busdecode." + (stems[stem] > 1 ? captureName(c, true) : stem);
        const std::string base = name;
        for (int n = 2; !taken.insert(name).second; ++n)
            name = fmt::format("{}_{}", base, n);
        out.push_back(name);
    }
    return out;
}

std::string xmlText(const std::string& s) {
    std::string out;
    out.reserve(s.size());
    for (std::size_t i = 0; i < s.size(); ++i) {
        const auto c = static_cast<unsigned char>(s[i]);
        if (c == '&')
            out += "&amp;";
        else if (c == '<')
            out += "&lt;";
        else if (c == '>')
            out += "&gt;";
        else if (c >= 0x80)  // a file name's Latin-1 byte would make the file invalid XML
            i += appendUtf8OrReplacement(out, s, i) - 1;
        else if (c >= 0x20 || c == '\n' || c == '\t')
            out += char(c);
    }
    return out;
}

std::string junitOpening(const JunitSuiteHead& head) {
    char stamp[32] = "1970-01-01T00:00:00";
    const std::time_t now = std::time(nullptr);
    std::tm tm{};
    if (gmtime_r(&now, &tm)) std::strftime(stamp, sizeof stamp, "%Y-%m-%dT%H:%M:%S", &tm);
    char host[256] = "localhost";
    gethostname(host, sizeof host - 1);

    std::string x = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
    // The root carries no attributes: the Ant schema allows none there (the counts are
    // on the one testsuite).
    x += "<testsuites>\n";
    x += fmt::format(
        "  <testsuite name=\"decode verify\" package=\"decode.verify\" id=\"0\" tests=\"{}\" "
        "failures=\"{}\" errors=\"{}\" skipped=\"0\" time=\"{:.3f}\" timestamp=\"{}\" "
        "hostname=\"{}\">\n",
        head.tests, head.failures, head.errors, head.seconds, stamp, xmlEscape(host));
    x += fmt::format("    <properties><property name=\"rules\" value=\"{}\"/>",
                     xmlEscape(head.rules_file));
    if (!head.shard.empty())
        x += fmt::format("<property name=\"shard\" value=\"{}\"/>", xmlEscape(head.shard));
    if (!head.checks.empty())
        x += fmt::format("<property name=\"checks\" value=\"{}\"/>", xmlEscape(head.checks));
    x += "</properties>\n";
    return x;
}

std::string junitCaseXml(const JunitCase& c) {
    std::string x = fmt::format("    <testcase name=\"{}\" classname=\"{}\" time=\"{}\"",
                                xmlEscape(c.name), xmlEscape(c.classname), xmlEscape(c.time));
    if (c.outcome.empty()) return x + "/>\n";
    return x +
           fmt::format(">\n      <{0} message=\"{1}\" type=\"{2}\">{3}</{0}>\n    </testcase>\n",
                       c.outcome, xmlEscape(c.message), xmlEscape(c.type), xmlEscape(c.text));
}

std::string junitClosing(const std::string& out, const std::string& err) {
    return fmt::format("    <system-out>{}</system-out>\n    <system-err>{}</system-err>\n",
                       xmlText(out), xmlText(err)) +
           "  </testsuite>\n</testsuites>\n";
}

std::string junitXml(const std::vector<CaptureVerdict>& all, const std::string& rules_file,
                     const std::string& shard, const std::string& checks) {
    JunitSuiteHead head{0, 0, 0, 0, rules_file, shard, checks};
    for (const auto& v : all) {
        head.seconds += v.seconds;
        if (v.input_error) {
            ++head.tests;
            ++head.errors;
            continue;
        }
        head.tests += v.outcomes.size();
        for (const auto& o : v.outcomes)
            head.failures += o.passed ? 0 : 1;
    }
    std::string x = junitOpening(head);
    const std::vector<std::string> class_names = junitClassNames(all);
    for (std::size_t i = 0; i < all.size(); ++i) {
        const CaptureVerdict& v = all[i];
        if (v.input_error) {
            x += junitCaseXml({"decode", class_names[i], fmt::format("{:.3f}", v.seconds), "error",
                               v.error, "input", v.error});
            continue;
        }
        // The capture's decode time is shared by its rules (they all ran in one pass).
        const double each = v.outcomes.empty() ? 0 : v.seconds / double(v.outcomes.size());
        for (const auto& o : v.outcomes)
            x += junitCaseXml({o.name(), class_names[i], fmt::format("{:.3f}", each),
                               o.passed ? "" : "failure", o.message, o.rule,
                               o.name() + ": " + o.message});
    }
    // What every rule saw, passed ones included, as the verify lines say it.
    std::string out;
    for (const auto& v : all) {
        out += verdictLine(v) + "\n";
        for (const auto& o : v.outcomes)
            out += fmt::format("  {} {}: {}\n", o.passed ? "pass" : "FAIL", o.name(), o.message);
    }
    std::string hints;  // as verify prints them on stderr
    for (const auto& v : all)
        for (const auto& h : v.hints)
            hints += hintLine(v.capture, h);
    x += junitClosing(out, hints);
    return x;
}

}  // namespace busdecode
