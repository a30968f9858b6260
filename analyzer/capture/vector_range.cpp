#include "vector_range.h"

#include <charconv>
#include <cstdlib>

#include <fmt/format.h>

namespace busdecode {

namespace {

std::optional<int> indexOf(std::string_view s) {
    int v = 0;
    const auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    if (s.empty() || ec != std::errc() || p != s.data() + s.size()) return std::nullopt;
    return v;
}

}  // namespace

std::optional<std::pair<int, int>> parseVectorRange(std::string_view text, int width) {
    if (text.size() < 5 || text.front() != '[' || text.back() != ']') return std::nullopt;
    text = text.substr(1, text.size() - 2);
    const auto colon = text.find(':');
    if (colon == std::string_view::npos) return std::nullopt;
    const auto msb = indexOf(text.substr(0, colon)), lsb = indexOf(text.substr(colon + 1));
    if (!msb || !lsb || *msb < 0 || *lsb < 0 || std::abs(std::int64_t(*msb) - *lsb) + 1 != width)
        return std::nullopt;  // negative indices (rare) keep 0 .. width-1
    return std::pair{*msb, *lsb};
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

}  // namespace busdecode
