// The BiSS-C decoder declared as data: roles, options, event types; and its factory.
#include <fmt/format.h>

#include "bissc_decoder.h"
#include "bissc_options.h"
#include "bissc_width_finder.h"

namespace busdecode {

namespace {

DecoderInfo bisscInfo() {
    DecoderInfo info;
    info.id = "bissc";
    info.name = "BiSS-C";
    info.description =
        "BiSS-C continuous mode (iC-Haus), point to point: frames with line-delay compensated "
        "sampling, processing time, CRC, and register accesses / commands carried by CDM/CDS";
    info.roles = {
        {"ma", true, {"clk", "clock", "mo"}, "master clock MA (as seen at the master)"},
        {"sl", true, {"slo", "data"}, "slave data SL (as seen at the master)"},
    };
    info.options = {
        intOption("bits", "26", 0, 64,
                  "data bits between CDS and nE (position, MT+ST); auto: the width under which "
                  "the first frames' CRCs are right",
                  true),
        intOption("st_bits", "auto", 0, 64,
                  "single-turn field width, LSB aligned (auto: bits - mt_bits)", true),
        intOption("mt_bits", "0", 0, 64, "multi-turn field width, above the single-turn field"),
        intOption("crc_poly", "0x43", 2, 0xFFFFFFFF,
                  "CRC polynomial in full notation (0x43 = x^6+x+1; 0x190D9 for CRC16)"),
        intOption("crc_bits", "auto", 0, 32, "CRC width (auto: from crc_poly; 0: frame has no CRC)",
                  true),
        intOption("crc_init", "0", 0, 0xFFFFFFFF, "CRC start value"),
        boolOption("crc_invert", "1",
                   "the CRC is sent inverted (BiSS); 0 for encoders that send the plain remainder"),
        numberOption(
            "timeout_min_us", "0", 0, 1e300,
            "flag timeout_short when SL rises sooner than this after the last MA rise (0: off)"),
    };
    using K = FieldSpec::Kind;
    info.events = {
        {"frame",
         "one BiSS-C frame (single-cycle data) with its timeout",
         {{"position", K::Int},     {"st", K::Int},
          {"mt", K::Int},           {"nE", K::Int},
          {"nW", K::Int},           {"crc_rx", K::Int},
          {"crc_ok", K::Bool},      {"cds", K::Int},
          {"cdm", K::Int},          {"line_delay_ns", K::Int},
          {"proc_cycles", K::Int},  {"ack_delay_ns", K::Int},
          {"clock_hz", K::Number},  {"timeout_ns", K::Int},
          {"extra_clocks", K::Int}, {"clocks", K::Int},
          {"bits", K::Int},         {"crc_bits", K::Int},
          {"hold_cdm", K::Bool},    {"retriggered", K::Bool}}},
        {"register",
         "a register read or write carried by CDM/CDS over many frames",
         {{"op", K::Text},
          {"id", K::Int},
          {"address", K::Int},
          {"data", K::Int},
          {"crc_ok", K::Bool},
          {"echo", K::Int},
          {"refused", K::Bool},
          {"busy_frames", K::Int},
          {"sequence", K::Int},
          {"idl", K::Int},
          {"frames", K::Int}}},
        {"command",
         "a control command (CTS = 0)",
         {{"id", K::Int},
          {"command", K::Int},
          {"crc_ok", K::Bool},
          {"broadcast", K::Bool},
          {"targets", K::IntList},
          {"ida", K::Int},
          {"executed", K::Bool}}},
    };
    return info;
}

}  // namespace

BisscSettings BisscSettings::from(const Options& o) {
    BisscSettings s;
    s.bits = int(o.integer("bits"));
    s.mt_bits = int(o.integer("mt_bits"));
    s.st_bits = o.isAuto("st_bits") ? std::max(0, s.bits - s.mt_bits) : int(o.integer("st_bits"));
    if (s.mt_bits > s.bits)  // st_bits=auto would be negative: name only what was given
        throw InputError(
            fmt::format("decoder bissc: mt_bits ({}) exceeds bits ({})", s.mt_bits, s.bits));
    if (s.st_bits + s.mt_bits > s.bits)
        throw InputError(fmt::format("decoder bissc: st_bits ({}) + mt_bits ({}) exceed bits ({})",
                                     s.st_bits, s.mt_bits, s.bits));
    const std::int64_t poly = o.integer("crc_poly");
    int width = 0;
    for (std::int64_t p = poly; p > 1; p >>= 1)
        ++width;
    s.crc_poly = std::uint32_t(poly);
    s.crc_bits = o.isAuto("crc_bits") ? width : int(o.integer("crc_bits"));
    if (s.crc_bits != 0 && s.crc_bits != width)
        throw InputError(fmt::format(
            "decoder bissc: crc_bits={} does not match crc_poly=0x{:X} (a {}-bit polynomial)",
            s.crc_bits, poly, width));
    s.crc_init = std::uint32_t(o.integer("crc_init"));
    s.crc_inverted = o.flag("crc_invert");
    s.timeout_min_ns = o.number("timeout_min_us") * 1000.0;
    return s;
}

namespace {

// A BisscDecoder, or with bits=auto the finder that picks its width first.
class BisscFactory : public DecoderFactory {
public:
    const DecoderInfo& info() const override { return info_; }
    std::unique_ptr<Decoder> create(const Options& o) const override {
        if (o.isAuto("bits")) return std::make_unique<BisscWidthFinder>(o);
        return std::make_unique<BisscDecoder>(o);
    }

private:
    DecoderInfo info_ = bisscInfo();
};

}  // namespace

std::shared_ptr<const DecoderFactory> makeBisscFactory() {
    return std::make_shared<BisscFactory>();
}

}  // namespace busdecode
