// verify(): captures checked against a rules file, as `decode verify` does, the verdicts
// handed to Python as plain data (busdecode/__init__.py makes them objects).
#include <pybind11/stl.h>

#include <cmath>

#include <fmt/format.h>

#include "bindings.h"
#include "core/options.h"
#include "core/sample_rate.h"
#include "decode_args_py.h"
#include "event_dict.h"
#include "verify/batch.h"
#include "verify/verify.h"

namespace busdecode::py {

namespace {

pyb::dict outcomeToPython(const RuleOutcome& o) {
    pyb::object first = o.first_ns ? pyb::object(pyb::float_(*o.first_ns)) : pyb::none();
    return pyb::dict(pyb::arg("name") = o.name(), pyb::arg("proto") = o.proto,
                     pyb::arg("rule") = o.rule, pyb::arg("passed") = o.passed,
                     pyb::arg("message") = o.message, pyb::arg("first_ns") = first,
                     pyb::arg("offending") = o.offending);
}

pyb::dict verdictToPython(const CaptureVerdict& v) {
    pyb::list outcomes;
    for (const auto& o : v.outcomes)
        outcomes.append(outcomeToPython(o));
    pyb::object error = v.input_error ? pyb::object(textToPython(v.error)) : pyb::none();
    return pyb::dict(pyb::arg("capture") = pathToPython(v.capture), pyb::arg("passed") = v.passed(),
                     pyb::arg("error") = error, pyb::arg("rules") = outcomes,
                     pyb::arg("events") = v.events, pyb::arg("seconds") = v.seconds,
                     pyb::arg("hints") = v.hints,
                     pyb::arg("summary") = textToPython(verdictLine(v)));
}

// (verdicts, summary line)
pyb::tuple verify(const std::vector<std::string>& captures, const std::string& rules,
                  const std::vector<std::string>& protos, const std::vector<std::string>& maps,
                  const std::vector<std::string>& opts, std::optional<double> rate, int jobs,
                  int threads, const std::vector<std::string>& thresholds,
                  const std::optional<std::string>& hysteresis) {
    if (captures.empty()) throw UsageError("no capture given");
    if (jobs < 0 || jobs > 256)
        throw UsageError("--jobs: expected a whole number from 0 (all cores) to 256");
    if (rate && !(*rate > 0 && std::isfinite(*rate)))
        throw UsageError(fmt::format("--rate {}: {}", *rate, kRateExpected));
    if (threads != 1 && threads != 2)
        throw UsageError(fmt::format(
            "--threads {}: expected 1 (read and decode on one thread) or 2 (read ahead on a "
            "second)",
            threads));
    DecodeArgs args;
    args.captures = captures;
    args.rules = rules;
    args.protos = protos;
    args.maps = maps;
    args.opts = opts;
    args.rate_hz = rate.value_or(0);
    args.jobs = jobs;
    args.threads = threads == 1 ? 1 : 2;
    OpenOptions analog;
    setAnalogOptions(analog, thresholds, hysteresis);
    args.thresholds = analog.thresholds;
    args.hysteresis = analog.hysteresis;
    std::vector<CaptureVerdict> verdicts;
    runInterruptibly([&](const std::atomic<bool>& stop) {
        VerifyPlan plan = planVerify(args);
        plan.open.stop = &stop;
        BatchOptions batch;
        batch.jobs = jobs;
        verdicts = verifyCaptures(captures, plan.rules, plan.requests, plan.open, batch, nullptr);
    });
    pyb::list out;
    for (const auto& v : verdicts)
        out.append(verdictToPython(v));
    return pyb::make_tuple(out, textToPython(summaryLine(verdicts)));
}

}  // namespace

void bindVerify(pyb::module_& m) {
    m.def("verify_captures", &verify, pyb::arg("captures"), pyb::arg("rules"), pyb::arg("protos"),
          pyb::arg("maps"), pyb::arg("opts"), pyb::arg("rate"), pyb::arg("jobs"),
          pyb::arg("threads"), pyb::arg("thresholds"), pyb::arg("hysteresis"));
}

}  // namespace busdecode::py
