// Weak fallbacks for the optional features, so the CLI links while a feature's
// module is being built; the real definitions (analyzer/lcm, analyzer/report,
// analyzer/verify) override these at link time.
#include "core/options.h"
#include "lcm/lcm_sink.h"
#include "report/report_sink.h"
#include "verify/verify.h"

namespace busdecode {

__attribute__((weak)) std::unique_ptr<OutputSink> makeLcmSink(const std::string&) {
    throw InputError("--lcm: this build has no LCM support");
}
__attribute__((weak)) int runMonitor(int, char**) { throw InputError("monitor: this build has no LCM support"); }
__attribute__((weak)) std::unique_ptr<OutputSink> makeReportSink(const std::string&) {
    throw InputError("--report: this build has no report support");
}
__attribute__((weak)) int runVerify(const DecodeArgs&) { throw InputError("verify: not in this build"); }

}  // namespace busdecode
