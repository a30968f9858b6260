#pragma once
// One event's captured waveform as an SVG: every line of its decoder as it was captured,
// the points where the decoder sampled the data (for SSI, BiSS-C and SPI), the bits read
// there with the decoded fields above them, and the measured line delay; an analog line's
// sampled voltage with its threshold and hysteresis band.
#include <map>
#include <string>

#include "core/time.h"
#include "edge_window.h"

namespace busdecode {

std::string waveformSvg(const FrameWave& w, const Timebase& tb,
                        const std::map<std::string, std::string>& options);

}  // namespace busdecode
