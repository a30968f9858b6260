#include "sample_rate.h"

#include <charconv>
#include <cmath>
#include <numeric>

#include <fmt/format.h>

#include "options.h"

namespace busdecode {

namespace {

// A decimal "12.5e-3" as mantissa * 10^exp10 (at most 18 significant digits).
struct Decimal {
    std::uint64_t mantissa = 0;
    int exp10 = 0;
};

std::optional<Decimal> parseDecimal(std::string_view s, std::size_t& used) {
    Decimal d;
    std::size_t i = 0;
    int digits = 0;
    bool point = false, any = false;
    for (; i < s.size(); ++i) {
        const char c = s[i];
        if (c == '.' && !point) {
            point = true;
            continue;
        }
        if (c < '0' || c > '9') break;
        any = true;
        if (d.mantissa == 0 && c == '0') {  // leading zeros are not significant
            if (point) --d.exp10;
            continue;
        }
        if (++digits > 18) return std::nullopt;  // more precision than a tick can hold
        d.mantissa = d.mantissa * 10 + std::uint64_t(c - '0');
        if (point) --d.exp10;
    }
    if (!any) return std::nullopt;
    if (i < s.size() && (s[i] == 'e' || s[i] == 'E')) {
        std::size_t j = i + 1;
        if (j < s.size() && s[j] == '+') ++j;  // from_chars takes '-' only
        int e = 0;
        auto [p, ec] = std::from_chars(s.data() + j, s.data() + s.size(), e);
        if (ec != std::errc() || p == s.data() + j || e < -400 || e > 400) return std::nullopt;
        d.exp10 += e;
        i = std::size_t(p - s.data());
    }
    used = i;
    return d;
}

int unitExponent(std::string_view unit) {
    std::string u;
    for (char c : unit)
        if (c != ' ' && c != '\t' && c != '\r')
            u += char(std::tolower(static_cast<unsigned char>(c)));
    if (u.empty() || u == "hz") return 0;
    if (u == "khz") return 3;
    if (u == "mhz") return 6;
    if (u == "ghz") return 9;
    return -1;
}

SampleRate fromDecimal(Decimal d) {
    if (d.mantissa == 0) return {std::nullopt, "is zero"};
    const double hz = double(d.mantissa) * std::pow(10.0, d.exp10);
    if (!(hz >= kMinSampleRateHz && hz <= kMaxSampleRateHz))
        return {std::nullopt, fmt::format("is out of range ({:g} Hz to {:g} Hz)", kMinSampleRateHz,
                                          kMaxSampleRateHz)};
    while (d.mantissa % 10 == 0) {
        d.mantissa /= 10;
        ++d.exp10;
    }
    if (d.exp10 < -18) return {std::nullopt, "has more digits than a tick can hold"};
    // hz = mantissa * 10^exp10, so one tick is 10^-exp10 / mantissa seconds; both terms
    // fit an int64 in the range above (mantissa < 10^18, exp10 from -18 to 15 here).
    Timebase tb;
    std::int64_t num = 1, den = std::int64_t(d.mantissa);
    for (int e = d.exp10; e > 0; --e)
        den *= 10;
    for (int e = d.exp10; e < 0; ++e)
        num *= 10;
    const std::int64_t g = std::gcd(num, den);
    tb.num = num / g;
    tb.den = den / g;
    return {tb, ""};
}

}  // namespace

SampleRate parseSampleRate(std::string_view text, bool units) {
    auto isSp = [](char c) { return c == ' ' || c == '\t' || c == '\r'; };
    while (!text.empty() && isSp(text.front()))
        text.remove_prefix(1);
    while (!text.empty() && isSp(text.back()))
        text.remove_suffix(1);
    if (!text.empty() && text.front() == '+') text.remove_prefix(1);
    std::size_t used = 0;
    auto d = parseDecimal(text, used);
    const int unit = d ? unitExponent(text.substr(used)) : -1;
    if (!d || unit < 0 || (!units && unit != 0) || (!units && used != text.size()))
        return {std::nullopt,
                units ? "is not a rate (like 24 MHz, 2.5 Hz or 1e6)" : "is not a number of Hz"};
    d->exp10 += unit;
    return fromDecimal(*d);
}

SampleRate sampleRateOf(double hz) {
    if (!std::isfinite(hz)) return {std::nullopt, "is not a number of Hz"};
    if (hz < 0) return {std::nullopt, "is negative"};
    char buf[64];
    auto [end, ec] = std::to_chars(buf, buf + sizeof buf, hz);  // shortest round trip
    if (ec != std::errc()) return {std::nullopt, "is not a number of Hz"};
    return parseSampleRate(std::string_view(buf, std::size_t(end - buf)), false);
}

double rateArgument(const std::string& option, const std::string& text) {
    auto hz = parseNumber(text);
    if (!hz) {  // with a unit, as --samplerate takes it ("1MHz", "24 MHz")
        const SampleRate rate = parseSampleRate(text, true);
        if (rate.timebase) hz = double(rate.timebase->den) / double(rate.timebase->num);
    }
    if (!hz || *hz <= 0) throw InputError(fmt::format("{} {}: {}", option, text, kRateExpected));
    const SampleRate rate = sampleRateOf(*hz);
    if (!rate.timebase) throw InputError(fmt::format("{} {}: {}", option, text, rate.problem));
    return *hz;
}

}  // namespace busdecode
