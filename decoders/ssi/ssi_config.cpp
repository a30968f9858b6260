#include "ssi_config.h"

#include <cctype>
#include <set>

#include <fmt/format.h>

#include "core/bit_word.h"

namespace busdecode {

namespace {

bool validName(const std::string& s) {
    if (s.empty()) return false;
    for (char c : s)
        if (!(std::isalnum((unsigned char)c) || c == '_' || c == '-')) return false;
    return true;
}

std::string trim(const std::string& s) {
    auto a = s.find_first_not_of(" \t");
    if (a == std::string::npos) return "";
    auto b = s.find_last_not_of(" \t");
    return s.substr(a, b - a + 1);
}

}  // namespace

std::uint64_t SsiConfig::dataMask() const {
    std::uint64_t m = lowBits(~std::uint64_t(0), bits);
    if (lead) m &= ~(std::uint64_t(1) << bitIndex(0));
    return m;
}

SsiConfig SsiConfig::fromOptions(const Options& o) {
    auto bad = [](const std::string& what) { return InputError("decoder ssi: " + what); };
    SsiConfig c;
    c.bits = int(o.integer("bits"));
    c.st_bits = int(o.integer("st_bits"));
    c.mt_bits = int(o.integer("mt_bits"));
    c.gray = o.flag("gray");
    c.tm_us = o.number("tm_us");
    c.lead = o.flag("lead");
    c.lsb_first = o.flag("lsb_first");
    c.sample_rising = o.text("sample_edge") == "rising";
    const std::string par = o.text("parity");
    c.parity = par == "even" ? SsiParity::Even : par == "odd" ? SsiParity::Odd : SsiParity::None;
    c.parity_msb = o.text("parity_pos") == "msb";
    if (o.isAuto("pos_shift"))
        c.pos_shift = (c.parity != SsiParity::None && !c.parity_msb) ? 1 : 0;
    else
        c.pos_shift = int(o.integer("pos_shift"));
    c.delay_auto = o.isAuto("delay_ns");
    c.delay_ns = c.delay_auto ? 0 : o.number("delay_ns");
    c.ring_gap = int(o.integer("ring_gap"));
    c.clock_min_hz = o.number("clock_min_hz");
    c.clock_max_hz = o.number("clock_max_hz");
    c.tm_min_us = o.isAuto("tm_min_us") ? c.tm_us / 2 : o.number("tm_min_us");
    c.tm_max_us = o.isAuto("tm_max_us") ? c.tm_us * 2 : o.number("tm_max_us");
    c.gap_bits = o.number("gap_bits");
    c.summary = o.flag("summary");

    if (c.lead && c.bits < 2) throw bad("lead=1 needs bits >= 2 (the lead bit and data)");
    if (c.st_bits + c.mt_bits + c.pos_shift > c.bits)
        throw bad(fmt::format("st_bits+mt_bits+pos_shift = {} exceeds bits={}",
                              c.st_bits + c.mt_bits + c.pos_shift, c.bits));
    if (c.clock_min_hz > c.clock_max_hz) throw bad("clock_min_hz is above clock_max_hz");
    if (c.tm_min_us > c.tm_max_us) throw bad("tm_min_us is above tm_max_us");

    // status_bits: NAME or NAME@BIT, comma separated; plain names take the bits above the
    // position field from the lowest up.
    static const std::set<std::string> reserved = {
        "raw",     "bits",         "position",         "st",     "mt",        "angle",
        "repeats", "repeat_match", "clock_hz",         "tm_ns",  "tp_ns",     "delay_ns",
        "reread",  "partial_bits", "repeat_diff_bits", "status", "parity_ok", "glitches"};
    const std::string spec = o.text("status_bits");
    int next_bit = c.pos_shift + c.st_bits + c.mt_bits;
    std::set<std::string> seen;
    std::size_t pos = 0;
    while (!spec.empty() && pos <= spec.size()) {
        auto comma = spec.find(',', pos);
        std::string item =
            trim(spec.substr(pos, comma == std::string::npos ? std::string::npos : comma - pos));
        pos = comma == std::string::npos ? spec.size() + 1 : comma + 1;
        int bit = next_bit;
        if (auto at = item.find('@'); at != std::string::npos) {
            auto n = parseInteger(trim(item.substr(at + 1)));
            if (!n) throw bad("status_bits: bad bit number in '" + item + "'");
            bit = int(*n);
            item = trim(item.substr(0, at));
        } else {
            ++next_bit;
        }
        if (item.empty()) continue;  // an unnamed bit
        if (!validName(item))
            throw bad("status_bits: '" + item + "' is not a name (letters, digits, _ and -)");
        if (bit < 0 || bit >= c.bits)
            throw bad(fmt::format("status_bits: {} is bit {}, outside the {}-bit word", item, bit,
                                  c.bits));
        if (!seen.insert(item).second) throw bad("status_bits: '" + item + "' named twice");
        c.status.push_back({reserved.count(item) ? "status_" + item : item, bit});
    }
    return c;
}

}  // namespace busdecode
