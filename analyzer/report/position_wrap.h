#pragma once
// Where a position wraps: an absolute encoder's word holds the position modulo 2^width
// (SSI and BiSS-C: single-turn plus multi-turn bits), so 65535 -> 0 on a 16-bit encoder
// is one count of motion, not a jump of 65535. Jumps, velocity and the verify rules use
// the shortest signed difference under that modulus.
#include <map>
#include <optional>
#include <string>

#include "core/event.h"

namespace busdecode {

class PositionWrap {
public:
    PositionWrap() = default;
    // `proto`: the decoder id; `options`: its options as resolved (CaptureFacts::options);
    // `override_modulus`: a modulus given by the user (0: positions do not wrap).
    PositionWrap(const std::string& proto, const std::map<std::string, std::string>& options,
                 std::optional<double> override_modulus = std::nullopt);
    // The modulus for this event's position (0: not modular).
    double modulus(const Event& e) const;
    // to - from, taken the short way round when the positions wrap.
    double difference(double from, double to, const Event& e) const;

private:
    enum class Kind { None, Fixed, BisscAutoWidth };
    Kind kind_ = Kind::None;
    double fixed_ = 0;
    int explicit_pos_bits_ = -1;  // BiSS-C with st_bits given: st_bits + mt_bits
    int mt_bits_ = 0;
};

// to - from folded into [-modulus/2, modulus/2) when modulus > 0.
double shortestDifference(double from, double to, double modulus);

}  // namespace busdecode
