#include "vector_range.h"

#include <charconv>
#include <cstdlib>

#include <tuple>

#include <fmt/format.h>

#include "core/options.h"

namespace busdecode {

std::optional<std::pair<int, int>> parseVectorRange(std::string_view text, int width) {
    if (text.size() < 5 || text.front() != '[' || text.back() != ']') return std::nullopt;
    text = text.substr(1, text.size() - 2);
    const auto colon = text.find(':');
    if (colon == std::string_view::npos) return std::nullopt;
    const auto msb = parseInteger(std::string(text.substr(0, colon)));
    const auto lsb = parseInteger(std::string(text.substr(colon + 1)));
    if (!msb || !lsb || *msb < 0 || *lsb < 0 || std::abs(*msb - *lsb) + 1 != width)
        return std::nullopt;  // negative indices (rare) keep 0 .. width-1
    return std::pair{int(*msb), int(*lsb)};
}

VectorName splitVectorName(std::string_view name, std::string_view after, int width) {
    VectorName v{std::string(name)};
    std::string_view range;
    const auto lb = name.find('[');
    if (width > 1 && lb != std::string_view::npos && lb > 0 && name.back() == ']') {
        range = name.substr(lb);
        v.ref.erase(lb);
    } else if (!after.empty() && after.front() == '[') {
        if (width > 1)
            range = after;
        else
            v.ref += after;
    }
    if (const auto r = parseVectorRange(range, width)) std::tie(v.msb, v.lsb) = *r;
    return v;
}

std::optional<int> bitAtIndex(const SignalInfo& s, std::int64_t i) {
    if (s.msb < 0) {
        if (i >= 0 && i < s.width) return int(i);
        return std::nullopt;
    }
    const std::int64_t bit = s.msb >= s.lsb ? i - s.lsb : s.lsb - i;
    if (bit >= 0 && bit < s.width) return int(bit);
    return std::nullopt;
}

std::string vectorRangeText(const SignalInfo& s) {
    if (s.width <= 1) return "";
    if (s.msb < 0) return fmt::format("[{}:0]", s.width - 1);
    return fmt::format("[{}:{}]", s.msb, s.lsb);
}

std::string signalText(const SignalInfo& s) {
    const std::string full = s.full_name + vectorRangeText(s);
    const bool named_by_path = s.full_name == s.name || s.full_name.ends_with("." + s.name);
    return named_by_path ? full : fmt::format("{} (column '{}')", s.name, full);
}

}  // namespace busdecode
