#include "junit_merge.h"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include <fmt/format.h>
#include <QXmlStreamReader>

#include "app/output_guard.h"
#include "core/atomic_file.h"
#include "core/options.h"
#include "shard.h"

namespace busdecode {

namespace {

std::string attr(const QXmlStreamReader& r, const char* name) {
    return r.attributes().value(QString::fromLatin1(name)).toString().toStdString();
}

std::string slurp(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(fmt::format("{}: cannot open", path));
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

// One <testcase>, the reader on its start tag; returns at its end tag.
JunitCase readCase(QXmlStreamReader& r) {
    JunitCase c{attr(r, "name"), attr(r, "classname"), attr(r, "time"), "", "", "", ""};
    while (r.readNextStartElement()) {
        const std::string tag = r.name().toString().toStdString();
        if (tag == "failure" || tag == "error") {
            c.outcome = tag;
            c.message = attr(r, "message");
            c.type = attr(r, "type");
            c.text = r.readElementText().toStdString();
        } else {
            r.skipCurrentElement();
        }
    }
    return c;
}

void readSuite(QXmlStreamReader& r, JunitShardFile& f) {
    while (r.readNextStartElement()) {
        const auto tag = r.name().toString().toStdString();
        if (tag == "properties") {
            while (r.readNextStartElement()) {
                const std::string name = attr(r, "name");
                if (name == "rules") f.rules = attr(r, "value");
                if (name == "shard") f.shard = attr(r, "value");
                if (name == "checks") f.checks = attr(r, "value");
                r.skipCurrentElement();
            }
        } else if (tag == "testcase") {
            f.cases.push_back(readCase(r));
        } else if (tag == "system-out") {
            f.out = r.readElementText().toStdString();
        } else if (tag == "system-err") {
            f.err = r.readElementText().toStdString();
        } else {
            r.skipCurrentElement();
        }
    }
}

}  // namespace

JunitShardFile readJunitShard(const std::string& path) {
    JunitShardFile f;
    f.path = path;
    const std::string text = slurp(path);
    QXmlStreamReader r(QByteArray::fromRawData(text.data(), qsizetype(text.size())));
    bool suite = false;
    if (r.readNextStartElement() && r.name() == QStringLiteral("testsuites"))
        while (r.readNextStartElement()) {
            if (r.name() != QStringLiteral("testsuite") || suite) {
                r.skipCurrentElement();
                continue;
            }
            suite = true;
            readSuite(r, f);
        }
    if (r.hasError())
        throw InputError(fmt::format("{}:{}: not well-formed JUnit XML: {}", path, r.lineNumber(),
                                     r.errorString().toStdString()));
    if (!suite) throw InputError(fmt::format("{}: no <testsuites><testsuite> in it", path));
    return f;
}

namespace {

// One <error> testcase (and its verify line) for a capture that has no verdict.
void addMissing(MergeResult& m, std::vector<JunitCase>& cases, std::string& out,
                const std::string& capture, const std::string& classname, const std::string& why) {
    cases.push_back({"decode", classname, "0.000", "error", why, "shard", why});
    CaptureVerdict v;
    v.capture = capture;
    v.input_error = true;
    v.error = why;
    out += verdictLine(v) + "\n";
    m.any_error = true;
}

// Every file's shard "K/N", checked to agree on N and to name each K once; N = 0 when
// the files come from whole runs (no shard property).
std::size_t shardCount(const std::vector<JunitShardFile>& files) {
    std::size_t n = 0;
    std::map<std::size_t, std::string> seen;
    for (const auto& f : files) {
        if (f.shard.empty()) {
            if (n)
                throw InputError(
                    fmt::format("{}: not from a --shard run, unlike the others", f.path));
            continue;
        }
        const Shard s = parseShard(f.shard, f.path + ": shard");
        if ((n && s.count != n) || (!n && &f != &files.front()))
            throw InputError(
                fmt::format("{}: shard {} does not match the other files", f.path, f.shard));
        n = s.count;
        if (!seen.emplace(s.index, f.path).second)
            throw InputError(
                fmt::format("{}: shard {} is also {}", f.path, f.shard, seen[s.index]));
    }
    return n;
}

BatchCounts countCaptures(const std::vector<JunitCase>& cases) {
    BatchCounts c;
    for (std::size_t i = 0; i < cases.size();) {
        std::size_t j = i;
        bool error = false, failure = false;
        for (; j < cases.size() && cases[j].classname == cases[i].classname; ++j) {
            error = error || cases[j].outcome == "error";
            failure = failure || cases[j].outcome == "failure";
            c.checks += cases[j].outcome == "error" ? 0 : 1;
            c.failed_checks += cases[j].outcome == "failure" ? 1 : 0;
        }
        ++c.captures;
        ++(error ? c.unreadable : failure ? c.failed : c.passed);
        i = j;
    }
    return c;
}

// A shard named its captures' classes over its own slice; the merged file names them as
// one run over the whole list does. Captures of the slice with no testcase become errors.
void renameShardCases(MergeResult& m, const JunitShardFile* f, std::vector<JunitCase>& cases,
                      std::string& out, const std::vector<std::string>& expected,
                      const std::vector<std::string>& global, const Shard& shard,
                      const std::string& why) {
    const std::vector<std::string> slice = shardOf(expected, shard);
    const std::vector<std::string> local = junitClassNames(slice);
    const std::size_t first = shardRange(expected.size(), shard).first;
    std::map<std::string, std::string> to_global;
    for (std::size_t i = 0; i < slice.size(); ++i)
        to_global[local[i]] = global[first + i];
    const std::size_t taken = f ? f->cases.size() : 0;
    std::set<std::string> in_shard, strangers;
    for (std::size_t i = cases.size() - taken; i < cases.size(); ++i) {
        auto it = to_global.find(cases[i].classname);
        if (it != to_global.end())
            cases[i].classname = it->second;
        else
            strangers.insert(cases[i].classname);
        in_shard.insert(cases[i].classname);
    }
    // A list other than the shards were run on: their totals would mean nothing.
    if (!strangers.empty())
        m.problems.push_back(fmt::format(
            "{}: {} of its captures are not in shard {} of the --from-list (first: {}): was it "
            "run on another list?",
            f->path, strangers.size(), shard.text(), *strangers.begin()));
    for (std::size_t i = 0; i < slice.size(); ++i)
        if (!in_shard.count(global[first + i]))
            addMissing(m, cases, out, slice[i], global[first + i], why);
}

// Shards checked against other rules are not one run.
void checkSameRules(const std::vector<JunitShardFile>& files) {
    for (const auto& f : files) {
        const JunitShardFile& first = files.front();
        if (f.rules != first.rules)
            throw InputError(fmt::format("{}: checked against the rules {}, {} against {}", f.path,
                                         f.rules, first.path, first.rules));
        // The same name, other contents or decoding options (a shard run elsewhere).
        if (f.checks != first.checks)
            throw InputError(
                fmt::format("{}: checked with other rules or decode options than {} "
                            "(the rules file's contents, --proto, --map, --opt, "
                            "--rate or --threshold differ)",
                            f.path, first.path));
    }
}

}  // namespace

MergeResult mergeJunit(const std::vector<JunitShardFile>& files,
                       const std::vector<std::string>& expected, bool list_given,
                       const std::vector<UnusableJunitFile>& unusable) {
    MergeResult m;
    checkSameRules(files);
    const std::size_t n = shardCount(files);
    std::vector<JunitCase> cases;
    std::string out, err;
    std::set<std::string> checked;
    auto take = [&](const JunitShardFile& f) {
        cases.insert(cases.end(), f.cases.begin(), f.cases.end());
        out += f.out;
        err += f.err;
        for (const auto& c : f.cases)
            checked.insert(c.classname);
    };
    // Class names as a single run over `expected` gives them (verdict.h junitClassNames).
    const std::vector<std::string> global = junitClassNames(expected);
    if (n == 0) {
        for (const auto& f : files)
            take(f);
        std::size_t missing = 0;
        for (std::size_t i = 0; i < expected.size(); ++i)
            if (!checked.count(global[i])) {
                addMissing(m, cases, out, expected[i], global[i],
                           "no verdict in any JUnit file given");
                ++missing;
            }
        if (missing)
            m.problems.push_back(
                fmt::format("{} of the list's {} captures have no verdict in any JUnit file given",
                            missing, expected.size()));
        if (!list_given)
            for (const auto& u : unusable)
                addMissing(m, cases, out, u.path, u.path, "no verdict: " + u.why);
    }
    for (std::size_t k = 1; k <= n; ++k) {
        const Shard shard{k, n};
        const auto f = std::find_if(files.begin(), files.end(),
                                    [&](const auto& f) { return f.shard == shard.text(); });
        const std::string why = fmt::format(
            "no verdict: shard {} {}", shard.text(),
            f == files.end() ? "wrote no usable JUnit file (failed, killed or never run)"
                             : "has no testcase for it");
        if (f == files.end()) {
            m.problems.push_back(fmt::format("shard {}: no usable JUnit file", shard.text()));
            if (!list_given)
                addMissing(m, cases, out, "shard " + shard.text(), "shard " + shard.text(), why);
        } else {
            take(*f);
        }
        if (list_given)
            renameShardCases(m, f == files.end() ? nullptr : &*f, cases, out, expected, global,
                             shard, why);
    }
    JunitSuiteHead head;
    head.rules_file = files.empty() ? "" : files.front().rules;
    head.checks = files.empty() ? "" : files.front().checks;
    for (const auto& c : cases) {
        ++head.tests;
        head.failures += c.outcome == "failure";
        head.errors += c.outcome == "error";
        head.seconds += parseNumber(c.time).value_or(0);
    }
    m.any_error = m.any_error || head.errors > 0 || !m.problems.empty();
    m.any_failure = head.failures > 0;
    m.summary = summaryLine(countCaptures(cases));
    m.xml = junitOpening(head);
    for (const auto& c : cases)
        m.xml += junitCaseXml(c);
    m.xml += junitClosing(out, err);
    return m;
}

namespace {

struct MergeArgs {
    std::vector<std::string> inputs;
    std::string output, from_list;
};

MergeArgs parseMergeArgs(int argc, char** argv) {
    MergeArgs a;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        auto value = [&]() -> std::string {
            if (i + 1 >= argc) throw InputError(fmt::format("{}: expected a FILE after it", arg));
            return argv[++i];
        };
        auto once = [&](std::string& slot) {
            if (!slot.empty())
                throw InputError(
                    fmt::format("{} is given more than once: it takes one value", arg));
            slot = value();
            if (slot.empty()) throw InputError(fmt::format("{}: expected a FILE, not ''", arg));
        };
        if (arg == "-o" || arg == "--output")
            once(a.output);
        else if (arg == "--from-list")
            once(a.from_list);
        else if (arg.size() > 1 && arg[0] == '-')
            throw InputError(fmt::format("{}: unknown option (see decode --help)", arg));
        else
            a.inputs.push_back(arg);
    }
    if (a.output.empty()) throw InputError("-o FILE is required");
    if (a.output == "-")
        throw InputError(
            "-o -: standard output carries the summary; name a file (/dev/stdout to "
            "share it)");
    if (a.inputs.empty() && a.from_list.empty()) throw InputError("no JUnit file given");
    for (const auto& in : a.inputs)
        if (in == a.output) throw InputError(fmt::format("-o {}: is also an input", in));
    std::vector<NamedFile> inputs;
    for (const auto& in : a.inputs)
        inputs.push_back({"JUnit file", in});
    if (!a.from_list.empty()) inputs.push_back({"capture list", a.from_list});
    refuseOutputOnInputs("-o", a.output, inputs);  // another spelling or a link of one
    return a;
}

}  // namespace

int runMergeJunit(int argc, char** argv) {
    try {
        const MergeArgs a = parseMergeArgs(argc, argv);
        const auto expected =
            a.from_list.empty() ? std::vector<std::string>{} : readCaptureList(a.from_list);
        checkWritable(a.output);
        std::vector<JunitShardFile> files;
        std::vector<UnusableJunitFile> unusable;
        for (const auto& in : a.inputs) {
            try {
                files.push_back(readJunitShard(in));
            } catch (const InputError& e) {
                unusable.push_back({in, e.what()});  // its shard counts as missing
            }
        }
        MergeResult m = mergeJunit(files, expected, !a.from_list.empty(), unusable);
        writeFileAtomically(a.output, m.xml);
        std::fputs((m.summary + "\n").c_str(), stdout);
        std::fflush(stdout);
        for (const auto& u : unusable)
            std::fprintf(stderr, "decode merge-junit: %s\n", u.why.c_str());
        for (const auto& p : m.problems)
            std::fprintf(stderr, "decode merge-junit: %s\n", p.c_str());
        return m.any_error || !unusable.empty() ? 2 : m.any_failure ? 1 : 0;
    } catch (const InputError& e) {
        std::fprintf(stderr, "decode merge-junit: %s\n", e.what());
        return 2;
    }
}

}  // namespace busdecode
