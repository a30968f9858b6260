#pragma once
// What `decode --device ...` asks of the analyser: the driver and its scan options, the
// sample rate, the channels and when to stop.
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace busdecode {

struct LiveSettings {
    std::string driver;  // a libsigrok driver ("demo", "fx2lafw") or "playback"
    // DRIVER:key=value:key=value (conn=..., serialcomm=..., playback's file=...)
    std::vector<std::pair<std::string, std::string>> options;
    std::uint64_t samplerate = 0;       // --samplerate (0: the device's current)
    std::vector<std::string> channels;  // --channels (empty: every logic channel)
    std::uint64_t samples = 0;          // --samples (0: no limit)
    double seconds = 0;                 // --time (0: no limit)
    std::string save;                   // --save FILE.sr ("" = none)
    std::string spec;                   // --device as given, to name it in messages
};

// Parses --device DRIVER[:key=value...]. Throws InputError naming the option.
LiveSettings parseDeviceSpec(const std::string& spec);

// How the run is named in messages and the summary ("demo", "playback:file=x.sr").
inline std::string liveCaptureName(const LiveSettings& s) {
    return s.spec.empty() ? s.driver : s.spec;
}

}  // namespace busdecode
