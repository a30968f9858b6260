#include "value_compare.h"

#include <cmath>

#include "sinks/event_format.h"

namespace busdecode::test {

namespace {

bool isIntegral(const Value& v) {
    return std::holds_alternative<std::int64_t>(v) || std::holds_alternative<std::uint64_t>(v) ||
           std::holds_alternative<bool>(v);
}

bool isNumber(const Value& v) {
    return isIntegral(v) || std::holds_alternative<double>(v);
}

// Non-finite doubles are written as null in JSON, so they mean "no value".
bool isNothing(const Value* v) {
    if (!v || isNull(*v)) return true;
    if (auto d = std::get_if<double>(v)) return !std::isfinite(*d);
    return false;
}

bool numbersEqual(const Value& a, const Value& b) {
    if (isIntegral(a) && isIntegral(b)) return asInt(a) == asInt(b);
    double x = asDouble(a), y = asDouble(b);
    return std::fabs(x - y) <= 1e-9 * std::max(std::fabs(x), std::fabs(y)) + 1e-9;
}

}  // namespace

std::string compareValues(const Value& got, const Value* want) {
    auto describe = [&] {
        return "lcm " + valueToJson(got) + " vs " + (want ? valueToJson(*want) : "missing");
    };
    if (isNothing(&got) || isNothing(want))
        return isNothing(&got) && isNothing(want) ? "" : describe();
    if (isNumber(got) && isNumber(*want)) return numbersEqual(got, *want) ? "" : describe();
    if (auto gl = std::get_if<std::vector<std::int64_t>>(&got)) {
        if (auto wl = std::get_if<std::vector<std::int64_t>>(want))
            return *gl == *wl ? "" : describe();
        if (isNumber(*want) && gl->size() == 1)
            return numbersEqual(Value{(*gl)[0]}, *want) ? "" : describe();
        return describe();
    }
    if (auto gs = std::get_if<std::string>(&got)) {
        if (auto ws = std::get_if<std::string>(want)) return *gs == *ws ? "" : describe();
        // The generic message carries lists as their JSON text.
        return *gs == valueToJson(*want) ? "" : describe();
    }
    return describe();
}

}  // namespace busdecode::test
