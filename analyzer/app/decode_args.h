#pragma once
// The decode command's arguments, shared by `decode` and `decode verify`: captures,
// --proto/--map/--opt (with `proto.` scoping when several decoders run), output choices.
#include <atomic>
#include <optional>
#include <string>
#include <vector>

#include "capture/capture_reader.h"
#include "core/session.h"

namespace busdecode {

struct DecodeArgs {
    std::vector<std::string> captures;
    std::vector<std::string> protos;     // --proto, in order
    std::vector<std::string> maps;       // --map ROLE=SIGNAL or PROTO.ROLE=SIGNAL
    std::vector<std::string> opts;       // --opt KEY=VALUE or PROTO.KEY=VALUE
    std::string format = "text";         // text | jsonl
    std::string report;                  // --report FILE ("" = none)
    std::optional<std::string> lcm_url;  // --lcm [URL] (empty string = LCM's default)
    double rate_hz = 0;                  // --rate
    bool follow = false;                 // --follow
    bool realtime = false;               // --realtime
    int threads = 2;                     // --threads N per capture: 1 or 2 (read ahead)
    // verify only
    std::string rules;  // --rules FILE
    std::string junit;  // --junit FILE
    int jobs = 0;       // --jobs N (0 = one per core)
};

// Turns --proto/--map/--opt into one request per decoder. An unscoped key applies to
// every decoder that declares it (an unscoped option no decoder declares is an error
// naming the valid ones); `ssi.bits=25` applies to ssi only. Throws InputError.
std::vector<DecoderRequest> buildRequests(const std::vector<std::string>& protos,
                                          const std::vector<std::string>& maps,
                                          const std::vector<std::string>& opts);

// A decoder's advice (CaptureFacts::advice) as a line for stderr (with --format jsonl and
// verify, whose stdout has no room for it): "decode: CAPTURE: hint: TEXT\n".
std::string hintLine(const std::string& capture, const std::string& hint);

// Opens one capture and decodes it into the sinks. Throws InputError on bad input.
CaptureFacts decodeCapture(const std::string& path, const std::vector<DecoderRequest>& requests,
                           const OpenOptions& open, const std::vector<OutputSink*>& sinks);
// The same, optionally paced at the capture's own time scale (--realtime) and stopped
// between blocks when *stop becomes true (Ctrl-C): a followed capture then ends as if
// it ended there; any other throws Interrupted (core/interrupted.h), its sinks not ended.
CaptureFacts decodeCapture(const std::string& path, const std::vector<DecoderRequest>& requests,
                           const OpenOptions& open, const std::vector<OutputSink*>& sinks,
                           bool realtime, const std::atomic<bool>* stop);

}  // namespace busdecode
