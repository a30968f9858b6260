// The SSI decoder's declaration (roles, options, events) and its entry in the registry.
#include "ssi_info.h"

#include <memory>

#include "core/registry.h"
#include "ssi_config.h"
#include "ssi_decoder.h"

namespace busdecode {

namespace {

DecoderInfo makeInfo() {
    DecoderInfo d;
    d.id = "ssi";
    d.name = "SSI absolute encoder";
    d.description =
        "Synchronous serial interface: clock from the master, data from the encoder. Words, "
        "multi-turn/single-turn fields, Gray code, multiple transmission, monoflop time.";
    d.roles = {
        {"clk", true, {"clock", "sclk", "ma", "cl"}, "clock from the master (idle high)"},
        {"data", true, {"dta", "do", "sl", "slo", "d"}, "data from the encoder (idle high)"},
    };
    const OptionSpec status = textOption(
        "status_bits", "",
        "names for bits above the position field, comma separated, lowest first (empty name "
        "skips a bit); NAME@N names raw bit N, e.g. out_of_range@23,low_quality@22");
    d.options = {
        intOption("bits", "25", 1, 64, "bits per word (the lead bit included)"),
        intOption("st_bits", "16", 0, 64, "single-turn field width (LSB aligned)"),
        intOption("mt_bits", "0", 0, 64, "multi-turn field width (above single-turn)"),
        boolOption("gray", "0", "the position field is Gray coded"),
        numberOption("tm_us", "20", 0, 1e300,
                     "nominal monoflop time: a burst starting while data is still low (within "
                     "tm_max of the last clock) is a re-read of the same word"),
        boolOption("lead", "0", "count the level sampled at the first sampling edge as a bit"),
        boolOption("lsb_first", "0", "the first bit on the wire is raw bit 0"),
        choiceOption("sample_edge", {"falling", "rising"},
                     "clock edge on which the master samples"),
        choiceOption("parity", {"none", "even", "odd"},
                     "parity over the whole word (even: the number of ones is even)"),
        choiceOption("parity_pos", {"lsb", "msb"}, "where the parity bit sits in the word"),
        intOption("pos_shift", "auto", 0, 63,
                  "bits below the position field (auto: 1 with parity at the LSB, else 0)", true),
        status,
        numberOption("delay_ns", "0", 0, 1e300,
                     "sample this long after each sampling edge; auto: the measured data delay",
                     true),
        intOption("ring_gap", "1", 0, 8, "zero bits between repeats of multiple transmission"),
        numberOption("clock_min_hz", "50e3", 0, 1e300, "lowest allowed clock (else clock_range)"),
        numberOption("clock_max_hz", "2e6", 0, 1e300, "highest allowed clock (else clock_range)"),
        numberOption("tm_min_us", "auto", 0, 1e300, "shortest allowed tm (auto: tm_us/2)", true),
        numberOption("tm_max_us", "auto", 0, 1e300, "longest allowed tm (auto: 2*tm_us)", true),
        numberOption("gap_bits", "3", 1.0, 1e300,
                     "the clock idle for this many clock periods ends a frame"),
        boolOption("summary", "1", "emit a summary event (tm min/median/max...) at the end"),
    };
    using K = FieldSpec::Kind;
    d.events = {
        {"frame",
         "one clock burst: the word and its fields",
         {{"raw", K::Int},
          {"bits", K::Int},
          {"position", K::Int},
          {"st", K::Int},
          {"mt", K::Int},
          {"angle", K::Number},
          {"repeats", K::Int},
          {"repeat_match", K::Bool},
          {"clock_hz", K::Number},
          {"tm_ns", K::Int},
          {"tp_ns", K::Int},
          {"delay_ns", K::Int},
          {"reread", K::Bool},
          {"partial_bits", K::Int},
          {"repeat_diff_bits", K::IntList},
          {"status", K::Int},
          {"<status_bits>", K::Bool},
          {"parity_ok", K::Bool},
          {"glitches", K::Int}}},
        {"summary",
         "statistics over the capture",
         {{"frames", K::Int},
          {"tm_min_ns", K::Int},
          {"tm_median_ns", K::Int},
          {"tm_max_ns", K::Int},
          {"clock_hz_min", K::Number},
          {"clock_hz_max", K::Number},
          {"repeat_mismatches", K::Int},
          {"short_frames", K::Int},
          {"error_frames", K::Int}}},
    };
    return d;
}

}  // namespace

const DecoderInfo& ssiInfo() {
    static const DecoderInfo info = makeInfo();
    return info;
}

std::shared_ptr<const DecoderFactory> makeSsiFactory() {
    return std::make_shared<SimpleFactory<SsiDecoder>>(ssiInfo());
}

}  // namespace busdecode
