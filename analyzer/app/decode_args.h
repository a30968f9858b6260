#pragma once
// The decode command's arguments, shared by `decode` and `decode verify`: captures,
// --proto/--map/--opt (with `proto.` scoping when several decoders run), output choices.
#include <atomic>
#include <optional>
#include <string>
#include <vector>

#include "capture/capture_reader.h"
#include "core/session.h"
#include "decode_capture.h"  // decodeCapture(), which takes the requests built here

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
    // --threshold [SIGNAL=]V and --hysteresis V (OpenOptions)
    std::vector<std::pair<std::string, double>> thresholds;
    double hysteresis = -1;
    bool follow = false;    // --follow
    bool realtime = false;  // --realtime
    int threads = 2;        // --threads N per capture: 1 or 2 (read ahead)
    // live acquisition (capture/live_device.h): --device, --samplerate, --channels,
    // --samples, --time, --save; --scan lists the devices
    std::string device;
    std::string samplerate, channels, samples, seconds, save;
    // verify only
    std::string rules;      // --rules FILE
    std::string junit;      // --junit FILE
    int jobs = 0;           // --jobs N (0 = one per core)
    std::string shard;      // --shard K/N ("" = the whole list)
    std::string from_list;  // --from-list FILE: more captures, one a line
};

// Turns --proto/--map/--opt into one request per decoder. An unscoped key applies to
// every decoder that declares it (an unscoped option no decoder declares is an error
// naming the valid ones); `ssi.bits=25` applies to ssi only. Each decoder's option values
// are checked here, once for every capture. Throws InputError.
std::vector<DecoderRequest> buildRequests(const std::vector<std::string>& protos,
                                          const std::vector<std::string>& maps,
                                          const std::vector<std::string>& opts);

// A decoder's advice (CaptureFacts::advice) as a line for stderr (with --format jsonl and
// verify, whose stdout has no room for it): "decode: CAPTURE: hint: TEXT\n".
std::string hintLine(const std::string& capture, const std::string& hint);

}  // namespace busdecode
