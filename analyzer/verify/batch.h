#pragma once
// Verifies a batch of captures, `jobs` at a time, and hands the verdicts back in input
// order whatever order the threads finish in (so --jobs never changes the output).
#include <functional>
#include <string>
#include <vector>

#include "core/session.h"
#include "rules.h"
#include "verdict.h"

namespace busdecode {

struct BatchOptions {
    int jobs = 1;           // captures at a time; 0 = one per core
    bool progress = false;  // draw a progress bar on stderr
};

// Decodes one capture through a RuleChecker. Input errors become an ERROR verdict, and
// so does a stop (open.stop set by Ctrl-C): the batch then starts no other capture.
CaptureVerdict verifyCapture(const std::string& capture, const Rules& rules,
                             const std::vector<DecoderRequest>& requests, const OpenOptions& open);

// `on_verdict` is called on the calling thread, in input order, as soon as each verdict
// and all before it are known.
std::vector<CaptureVerdict> verifyCaptures(
    const std::vector<std::string>& captures, const Rules& rules,
    const std::vector<DecoderRequest>& requests, const OpenOptions& open, const BatchOptions& batch,
    const std::function<void(const CaptureVerdict&)>& on_verdict);

// --proto/--map/--opt of the batch: the command line's, on top of the rules' [decode]
// table (a command-line KEY replaces the same KEY from the rules). Without any --proto,
// the decoders named by the rules' tables run.
struct DecodeChoice {
    std::vector<std::string> protos, maps, opts;
};
DecodeChoice combineDecodeChoice(const Rules& rules, const std::vector<std::string>& cli_protos,
                                 const std::vector<std::string>& cli_maps,
                                 const std::vector<std::string>& cli_opts);

}  // namespace busdecode
