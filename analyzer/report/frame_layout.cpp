#include "frame_layout.h"

#include <cstdint>

namespace busdecode {

namespace {

std::optional<std::int64_t> intField(const Event& e, std::string_view key) {
    const Value* v = e.get(key);
    if (!v || isNull(*v) || std::holds_alternative<std::string>(*v)) return std::nullopt;
    return asInt(*v);
}

std::vector<int> msbFirst(std::uint64_t value, int width) {
    std::vector<int> bits;
    for (int i = width - 1; i >= 0; --i)
        bits.push_back(int((value >> i) & 1));
    return bits;
}

}  // namespace

bool fieldShowsFault(const Event& e, const Field& f) {
    // Only bools that say something is right (crc_ok, repeat_match, consistent...) are
    // faults when false; others (hold_cdm, retriggered) are just states.
    if (auto b = std::get_if<bool>(&f.value)) {
        const std::string& k = f.key;
        const bool says_ok = k == "consistent" ||
                             (k.size() > 3 && k.compare(k.size() - 3, 3, "_ok") == 0) ||
                             (k.size() > 6 && k.compare(k.size() - 6, 6, "_match") == 0);
        return says_ok && !*b;
    }
    if ((f.key == "nE" || f.key == "nW") && !isNull(f.value)) return asInt(f.value) == 0;
    if (f.key == "crc_rx") return e.hasError("crc");
    return false;
}

std::vector<BitSegment> frameLayout(const Event& e) {
    std::vector<BitSegment> out;
    auto bits = intField(e, "bits");

    if (e.proto == "bissc" && e.type == "frame") {
        const auto pos = intField(e, "position");
        const auto proc = intField(e, "proc_cycles").value_or(0);
        // Without a `bits` field the width follows from the MA rising edges counted:
        // LAT, ACK, busy clocks, S, CDS, data, nE, nW, 6 CRC bits, STP, extra clocks.
        if (!bits) {
            if (auto clocks = intField(e, "clocks"))
                bits = *clocks - intField(e, "extra_clocks").value_or(0) - proc - 13;
        }
        if (!pos || !bits || *bits <= 0 || *bits > 64) return out;
        out.push_back(
            {"ACK", std::vector<int>(std::size_t(1 + std::max<std::int64_t>(proc, 0)), 0), false});
        out.push_back({"S", {1}, false});
        out.push_back({"CDS", {int(intField(e, "cds").value_or(0) & 1)}, false});
        out.push_back({"POS", msbFirst(std::uint64_t(*pos), int(*bits)), false});
        const int ne = int(intField(e, "nE").value_or(1) & 1);
        const int nw = int(intField(e, "nW").value_or(1) & 1);
        out.push_back({"nE", {ne}, ne == 0});
        out.push_back({"nW", {nw}, nw == 0});
        if (auto crc = intField(e, "crc_rx"))
            out.push_back({"CRC", msbFirst(std::uint64_t(*crc), 6), e.hasError("crc")});
        out.push_back({"STP", {0}, false});
        return out;
    }
    if (!bits || *bits <= 0 || *bits > 64) return out;
    if (auto raw = intField(e, "raw")) {
        out.push_back({"DATA", msbFirst(std::uint64_t(*raw), int(*bits)),
                       e.hasError("repeat_mismatch") || e.hasError("short_frame")});
    }
    return out;
}

}  // namespace busdecode
