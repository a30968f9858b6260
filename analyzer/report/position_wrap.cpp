#include "position_wrap.h"

#include <algorithm>
#include <cmath>

#include "core/options.h"

namespace busdecode {

namespace {

// An integer option as resolved; nullopt for "auto" or when absent.
std::optional<std::int64_t> intOption(const std::map<std::string, std::string>& options,
                                      const std::string& key) {
    auto it = options.find(key);
    if (it == options.end()) return std::nullopt;
    return parseInteger(it->second);
}

double powerOfTwo(std::int64_t bits) {
    return bits > 0 && bits <= 64 ? std::ldexp(1.0, int(bits)) : 0.0;
}

}  // namespace

PositionWrap::PositionWrap(const std::string& proto,
                           const std::map<std::string, std::string>& options,
                           std::optional<double> override_modulus) {
    if (override_modulus) {
        kind_ = *override_modulus > 0 ? Kind::Fixed : Kind::None;
        fixed_ = *override_modulus;
        return;
    }
    if (proto == "ssi") {
        const auto st = intOption(options, "st_bits"), mt = intOption(options, "mt_bits");
        if (st && mt && (fixed_ = powerOfTwo(*st + *mt)) > 0) kind_ = Kind::Fixed;
    } else if (proto == "bissc") {
        // The position is min(bits, st_bits + mt_bits) wide; bits may be found from the
        // traffic (bits=auto), and every frame carries the width it was decoded with.
        mt_bits_ = int(intOption(options, "mt_bits").value_or(0));
        if (const auto st = intOption(options, "st_bits")) explicit_pos_bits_ = int(*st) + mt_bits_;
        kind_ = Kind::BisscAutoWidth;
    }
}

double PositionWrap::modulus(const Event& e) const {
    switch (kind_) {
        case Kind::None:
            return 0;
        case Kind::Fixed:
            return fixed_;
        case Kind::BisscAutoWidth: {
            const Value* bits = e.get("bits");
            if (!bits || !std::holds_alternative<std::int64_t>(*bits)) return 0;
            std::int64_t width = std::get<std::int64_t>(*bits);
            if (explicit_pos_bits_ >= 0) width = std::min<std::int64_t>(width, explicit_pos_bits_);
            return powerOfTwo(width);
        }
    }
    return 0;
}

double PositionWrap::difference(double from, double to, const Event& e) const {
    return shortestDifference(from, to, modulus(e));
}

double shortestDifference(double from, double to, double modulus) {
    const double d = to - from;
    if (modulus <= 0) return d;
    double folded = std::fmod(d, modulus);
    if (folded < -modulus / 2) folded += modulus;
    if (folded >= modulus / 2) folded -= modulus;
    return folded;
}

}  // namespace busdecode
