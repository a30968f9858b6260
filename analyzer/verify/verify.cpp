#include "verify.h"

#include <cstdio>

#include <unistd.h>

#include <fmt/format.h>

#include "app/decode_args.h"
#include "app/plugin_loader.h"
#include "batch.h"
#include "core/atomic_file.h"
#include "core/options.h"
#include "core/registry.h"
#include "rules.h"

namespace busdecode {

int runVerify(const DecodeArgs& args) {
    try {
        loadPlugins();  // every one: the rules may name any decoder
        std::vector<std::string> known;
        for (const auto* f : Registry::instance().all())
            known.push_back(f->info().id);
        const Rules rules = loadRules(args.rules, known);
        const DecodeChoice choice = combineDecodeChoice(rules, args.protos, args.maps, args.opts);
        const auto requests = buildRequests(choice.protos, choice.maps, choice.opts);
        if (args.captures.empty()) throw InputError("decode verify: no capture given");
        if (!args.junit.empty()) checkWritable(args.junit);  // before a long batch, not after

        OpenOptions open;
        open.rate_hz = args.rate_hz > 0 ? args.rate_hz : rules.decode.rate_hz;
        open.read_ahead = args.threads > 1;
        BatchOptions batch;
        batch.jobs = args.jobs;
        batch.progress = ::isatty(STDERR_FILENO) && args.captures.size() > 1;
        const auto verdicts = verifyCaptures(
            args.captures, rules, requests, open, batch, [](const CaptureVerdict& v) {
                fmt::print("{}\n", verdictLine(v));
                std::fflush(stdout);
                // stdout keeps one line per capture
                for (const auto& h : v.hints)
                    std::fputs(hintLine(v.capture, h).c_str(), stderr);
            });
        fmt::print("{}\n", summaryLine(verdicts));
        std::fflush(stdout);
        if (!args.junit.empty()) writeFileAtomically(args.junit, junitXml(verdicts, args.rules));

        bool any_error = false, any_fail = false;
        for (const auto& v : verdicts) {
            any_error = any_error || v.input_error;
            any_fail = any_fail || !v.passed();
        }
        // One line per unreadable capture, naming it once (most messages start with it).
        for (const auto& v : verdicts)
            if (v.input_error) {
                const bool named = v.error.rfind(v.capture + ":", 0) == 0;
                fmt::print(stderr, "decode verify: {}{}\n", named ? "" : v.capture + ": ", v.error);
            }
        return any_error ? 2 : any_fail ? 1 : 0;
    } catch (const InputError& e) {
        std::fflush(stdout);
        fmt::print(stderr, "decode verify: {}\n", oneLine(e.what()));
        return 2;
    }
}

}  // namespace busdecode
