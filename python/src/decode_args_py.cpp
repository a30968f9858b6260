#include "decode_args_py.h"

#include <cmath>

#include <fmt/format.h>

#include "bindings.h"
#include "capture/analog_lines.h"
#include "core/options.h"
#include "core/sample_rate.h"

namespace busdecode::py {

DecodeJob jobFor(const CaptureArgs& a, bool follow) {
    if (a.rate && !(*a.rate > 0 && std::isfinite(*a.rate)))
        throw UsageError(fmt::format("--rate {}: {}", *a.rate, kRateExpected));
    if (a.threads != 1 && a.threads != 2)
        throw UsageError(fmt::format(
            "--threads {}: expected 1 (read and decode on one thread) or 2 (read ahead on a "
            "second)",
            a.threads));
    DecodeJob job;
    job.path = a.path;
    job.requests = requestsFor(a.protos, a.maps, a.opts);
    job.open.rate_hz = a.rate.value_or(0);
    job.open.follow = follow;
    job.open.read_ahead = a.threads > 1;
    setAnalogOptions(job.open, a.thresholds, a.hysteresis);
    return job;
}

void setAnalogOptions(OpenOptions& open, const std::vector<std::string>& thresholds,
                      const std::optional<std::string>& hysteresis) {
    try {
        for (const auto& t : thresholds)
            open.thresholds.push_back(parseThresholdOption(t));
        if (hysteresis) open.hysteresis = parseHysteresisOption(*hysteresis);
    } catch (const InputError& e) {
        throw UsageError(e.what());
    }
}

}  // namespace busdecode::py
