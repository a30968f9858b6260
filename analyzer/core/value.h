#pragma once
// A typed field value of a decoded event. Results are data (like Saleae's FrameV2);
// text and JSON are rendered later by the sinks.
#include <cstdint>
#include <string>
#include <variant>
#include <vector>

namespace busdecode {

struct Null {
    bool operator==(const Null&) const = default;
};

using Value = std::variant<Null, bool, std::int64_t, std::uint64_t, double, std::string,
                           std::vector<std::int64_t>>;

inline bool isNull(const Value& v) {
    return std::holds_alternative<Null>(v);
}
// Numeric view of integers, bools and doubles (NaN for others); handy in rules and stats.
double asDouble(const Value& v);
// Integer view (0 for non-numeric); doubles are truncated.
std::int64_t asInt(const Value& v);

}  // namespace busdecode
