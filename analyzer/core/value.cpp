#include "value.h"

#include <cmath>

namespace busdecode {

double asDouble(const Value& v) {
    if (auto p = std::get_if<bool>(&v)) return *p ? 1.0 : 0.0;
    if (auto p = std::get_if<std::int64_t>(&v)) return double(*p);
    if (auto p = std::get_if<std::uint64_t>(&v)) return double(*p);
    if (auto p = std::get_if<double>(&v)) return *p;
    return std::nan("");
}

std::int64_t asInt(const Value& v) {
    if (auto p = std::get_if<bool>(&v)) return *p ? 1 : 0;
    if (auto p = std::get_if<std::int64_t>(&v)) return *p;
    if (auto p = std::get_if<std::uint64_t>(&v)) return std::int64_t(*p);
    if (auto p = std::get_if<double>(&v)) return std::isfinite(*p) ? std::int64_t(*p) : 0;
    return 0;
}

}  // namespace busdecode
