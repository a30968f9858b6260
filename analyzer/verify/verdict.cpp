#include "verdict.h"

#include <cctype>
#include <ctime>
#include <filesystem>
#include <map>
#include <set>

#include <unistd.h>

#include <fmt/format.h>

#include "app/decode_args.h"

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
    std::size_t pass = 0, fail = 0, err = 0, checks = 0, failed_checks = 0;
    for (const auto& v : all) {
        if (v.input_error)
            ++err;
        else if (v.passed())
            ++pass;
        else
            ++fail;
        for (const auto& o : v.outcomes) {
            ++checks;
            if (!o.passed) ++failed_checks;
        }
    }
    return fmt::format(
        "{} capture{}: {} passed, {} failed, {} unreadable; {} rule checks, {} failed", all.size(),
        all.size() == 1 ? "" : "s", pass, fail, err, checks, failed_checks);
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
    std::map<std::string, int> stems;
    for (const auto& v : all)
        ++stems[captureName(v.capture, false)];
    std::vector<std::string> out;
    std::set<std::string> taken;
    for (const auto& v : all) {
        const std::string stem = captureName(v.capture, false);
        std::string name = "busdecode." + (stems[stem] > 1 ? captureName(v.capture, true) : stem);
        const std::string base = name;
        for (int n = 2; !taken.insert(name).second; ++n)
            name = fmt::format("{}_{}", base, n);
        out.push_back(name);
    }
    return out;
}

namespace {
// Character data keeps its line breaks; attributes (xmlEscape) encode them.
std::string xmlText(const std::string& s) {
    std::string out;
    out.reserve(s.size());
    for (unsigned char c : s) {
        if (c == '&')
            out += "&amp;";
        else if (c == '<')
            out += "&lt;";
        else if (c == '>')
            out += "&gt;";
        else if (c >= 0x20 || c == '\n' || c == '\t')
            out += char(c);
    }
    return out;
}
}  // namespace

std::string junitXml(const std::vector<CaptureVerdict>& all, const std::string& rules_file) {
    std::size_t tests = 0, failures = 0, errors = 0;
    double total = 0;
    for (const auto& v : all) {
        total += v.seconds;
        if (v.input_error) {
            ++tests;
            ++errors;
            continue;
        }
        tests += v.outcomes.size();
        for (const auto& o : v.outcomes)
            failures += o.passed ? 0 : 1;
    }
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
        tests, failures, errors, total, stamp, xmlEscape(host));
    x += fmt::format("    <properties><property name=\"rules\" value=\"{}\"/></properties>\n",
                     xmlEscape(rules_file));
    const std::vector<std::string> class_names = junitClassNames(all);
    for (std::size_t i = 0; i < all.size(); ++i) {
        const CaptureVerdict& v = all[i];
        const std::string cls = xmlEscape(class_names[i]);
        if (v.input_error) {
            x += fmt::format("    <testcase name=\"decode\" classname=\"{}\" time=\"{:.3f}\">\n",
                             cls, v.seconds);
            x += fmt::format("      <error message=\"{}\" type=\"input\">{}</error>\n",
                             xmlEscape(v.error), xmlEscape(v.error));
            x += "    </testcase>\n";
            continue;
        }
        // The capture's decode time is shared by its rules (they all ran in one pass).
        const double each = v.outcomes.empty() ? 0 : v.seconds / double(v.outcomes.size());
        for (const auto& o : v.outcomes) {
            x += fmt::format("    <testcase name=\"{}\" classname=\"{}\" time=\"{:.3f}\"",
                             xmlEscape(o.name()), cls, each);
            if (o.passed) {
                x += "/>\n";
            } else {
                x += ">\n";
                x += fmt::format("      <failure message=\"{}\" type=\"{}\">{}</failure>\n",
                                 xmlEscape(o.message), xmlEscape(o.rule),
                                 xmlEscape(o.name() + ": " + o.message));
                x += "    </testcase>\n";
            }
        }
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
    x += fmt::format("    <system-out>{}</system-out>\n    <system-err>{}</system-err>\n",
                     xmlText(out), xmlText(hints));
    x += "  </testsuite>\n</testsuites>\n";
    return x;
}

}  // namespace busdecode
