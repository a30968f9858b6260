#pragma once
// Where a decoder read each bit of an event, found again from the captured edges and the
// decoder's options (the decoders hand over events, not sample times): the clock edges
// that sample SSI, BiSS-C and SPI, the mid-bit points after each start edge for UART and
// TMCL; and which field each bit belongs to. The waveform drawing marks them.
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/time.h"
#include "edge_window.h"

namespace busdecode {

// Where the decoder read each bit, and which field each bit belongs to.
struct SamplePlan {
    std::string clock_role, data_role;
    std::vector<double> t_ns{};  // one per bit, in wire order
    struct Segment {
        std::string label;
        std::size_t first = 0, count = 0;
        bool fault = false;
    };
    std::vector<Segment> segments{};
    std::optional<double> delay_ns{};  // measured line delay, drawn after `delay_from_ns`
    double delay_from_ns = 0;
};

SamplePlan planFor(const FrameWave& w, const Timebase& tb,
                   const std::map<std::string, std::string>& options);

}  // namespace busdecode
