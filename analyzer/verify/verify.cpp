#include "verify.h"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <iterator>

#include <unistd.h>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "app/decode_args.h"
#include "app/interruption.h"
#include "app/output_guard.h"
#include "app/plugin_loader.h"
#include "app/standard_streams.h"
#include "batch.h"
#include "core/atomic_file.h"
#include "core/options.h"
#include "core/registry.h"
#include "rules.h"
#include "shard.h"

namespace busdecode {

namespace {

// A table for a decoder this run does not decode would pass with nothing checked (a typo
// in --proto turning CI green).
void refuseTablesOfDecodersNotRun(const Rules& rules, const std::vector<DecoderRequest>& requests) {
    std::vector<std::string> run;
    for (const auto& r : requests)
        run.push_back(r.proto);
    for (const auto& t : rules.tables) {
        const std::string id = t.proto.substr(0, t.proto.find('#'));  // "ssi#2": an instance
        if (t.proto == kSignalTable || std::find(run.begin(), run.end(), id) != run.end()) continue;
        throw InputError(fmt::format(
            "{}:{}: [{}]: no such decoder in this run (decoding with {}): give --proto {} or "
            "remove the table",
            rules.file, t.line, t.proto, fmt::join(run, ", "), id));
    }
}

// FNV-1a, 64 bits: a digest to tell two shards' checks apart, not a security measure.
std::string checksDigest(const std::string& rules_path, const VerifyPlan& plan) {
    std::ifstream in(rules_path, std::ios::binary);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    for (const auto& r : plan.requests)
        text +=
            fmt::format("\n{} {} {}", r.proto, fmt::join(r.map, ","), fmt::join(r.options, ","));
    text += fmt::format("\n{} {} {}", plan.open.rate_hz, plan.open.hysteresis,
                        fmt::join(plan.open.thresholds, ","));
    std::uint64_t h = 14695981039346656037ull;
    for (const unsigned char c : text)
        h = (h ^ c) * 1099511628211ull;
    return fmt::format("fnv1a64:{:016x}", h);
}

}  // namespace

VerifyPlan planVerify(const DecodeArgs& args) {
    loadPlugins();  // every one: the rules may name any decoder
    std::vector<std::string> known;
    for (const auto* f : Registry::instance().all())
        known.push_back(f->info().id);
    VerifyPlan plan;
    plan.rules = loadRules(args.rules, known);
    const DecodeChoice choice = combineDecodeChoice(plan.rules, args.protos, args.maps, args.opts);
    plan.requests = buildRequests(choice.protos, choice.maps, choice.opts);
    refuseTablesOfDecodersNotRun(plan.rules, plan.requests);
    plan.open.rate_hz = args.rate_hz > 0 ? args.rate_hz : plan.rules.decode.rate_hz;
    plan.open.thresholds = args.thresholds;
    plan.open.hysteresis = args.hysteresis;
    plan.open.read_ahead = args.threads > 1;
    plan.checks = checksDigest(args.rules, plan);
    return plan;
}

namespace {

// The command line's captures, then --from-list's: every shard's.
std::vector<std::string> allCaptures(const DecodeArgs& args) {
    std::vector<std::string> all = args.captures;
    if (!args.from_list.empty()) {
        auto listed = readCaptureList(args.from_list);
        all.insert(all.end(), listed.begin(), listed.end());
    }
    return all;
}

}  // namespace

int runVerify(const DecodeArgs& args) {
    try {
        const std::string shard = args.shard.empty() ? "" : parseShard(args.shard).text();
        const VerifyPlan plan = planVerify(args);
        const Rules& rules = plan.rules;
        const std::vector<std::string> named = allCaptures(args);
        const std::vector<std::string> captures =
            args.shard.empty() ? named : shardOf(named, parseShard(args.shard));
        // Every shard of an empty list would pass with nothing checked.
        if (named.empty())
            throw InputError(args.from_list.empty()
                                 ? "no capture given"
                                 : fmt::format("{}: the list names no capture", args.from_list));
        if (!args.junit.empty()) {
            refuseOutputOnInputs("--junit", args.junit, runInputs(args, named));
            checkWritable(args.junit);  // before a long batch, not after
        }

        OpenOptions open = plan.open;
        open.stop = interruptionFlag();
        BatchOptions batch;
        batch.jobs = args.jobs;
        batch.progress = ::isatty(STDERR_FILENO) && captures.size() > 1;
        std::size_t printed = 0;
        const auto verdicts = verifyCaptures(
            captures, rules, plan.requests, open, batch, [&](const CaptureVerdict& v) {
                if (interrupted()) return;  // what follows was cut short
                std::fputs((verdictLine(v) + "\n").c_str(), stdout);
                std::fflush(stdout);
                ++printed;
                // stdout keeps one line per capture
                for (const auto& h : v.hints)
                    printError(hintLine(v.capture, h));
            });
        if (interrupted()) {
            printError(
                fmt::format("decode verify: interrupted ({}) after {} of {} captures{}\n",
                            interruptingSignalName(), printed, verdicts.size(),
                            args.junit.empty() ? "" : "; nothing written to the JUnit file"));
            return interruptedStatus();
        }
        std::fputs((summaryLine(verdicts) + "\n").c_str(), stdout);
        checkStandardOutput();
        if (!args.junit.empty())
            writeFileAtomically(args.junit, junitXml(verdicts, args.rules, shard, plan.checks));

        bool any_error = false, any_fail = false;
        for (const auto& v : verdicts) {
            any_error = any_error || v.input_error;
            any_fail = any_fail || !v.passed();
        }
        // One line per unreadable capture, naming it once (most messages start with it).
        for (const auto& v : verdicts)
            if (v.input_error) {
                const bool named = v.error.rfind(v.capture + ":", 0) == 0;
                printError(
                    fmt::format("decode verify: {}{}\n", named ? "" : v.capture + ": ", v.error));
            }
        return any_error ? 2 : any_fail ? 1 : 0;
    } catch (const InputError& e) {
        std::fflush(stdout);
        printError(fmt::format("decode verify: {}\n", oneLine(e.what())));
        return 2;
    }
}

}  // namespace busdecode
