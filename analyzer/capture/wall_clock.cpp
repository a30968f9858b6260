#include "wall_clock.h"

#include <ctime>

#include <fmt/format.h>

namespace busdecode {

namespace {

std::string iso(const std::tm& tm) {
    return fmt::format("{:04}-{:02}-{:02}T{:02}:{:02}:{:02}", tm.tm_year + 1900, tm.tm_mon + 1,
                       tm.tm_mday, tm.tm_hour, tm.tm_min, tm.tm_sec);
}

}  // namespace

std::string wallClockFromText(const std::string& text) {
    const auto a = text.find_first_not_of(" \t\r\n");
    if (a == std::string::npos) return {};
    const std::string s = text.substr(a, text.find_last_not_of(" \t\r\n") - a + 1);
    static const char* const layouts[] = {
        "%a %b %d %H:%M:%S %Y",  // Icarus, GTKWave, sigrok, Verilator: asctime()
        "%Y-%m-%dT%H:%M:%S",     // ISO 8601
        "%Y-%m-%d %H:%M:%S",
        "%b %d, %Y %H:%M:%S",  // ModelSim / Questa
        "%a %b %d %H:%M:%S %Z %Y",
        "%d-%b-%Y %H:%M:%S",  // LeCroy
    };
    for (const char* layout : layouts) {
        std::tm tm{};
        const char* end = strptime(s.c_str(), layout, &tm);
        if (end && *end == '\0') return iso(tm);
    }
    return s;
}

std::string wallClockFromUnixMs(std::int64_t ms) {
    const std::int64_t ms_part = ((ms % 1000) + 1000) % 1000;
    const std::time_t seconds = std::time_t((ms - ms_part) / 1000);
    std::tm tm{};
    if (!gmtime_r(&seconds, &tm)) return {};
    return fmt::format("{}.{:03}Z", iso(tm), ms_part);
}

std::string wallClockOfSigrokComment(std::string_view comment) {
    const auto a = comment.find_first_not_of("; \t");
    if (a == std::string_view::npos || comment.substr(a).rfind("from ", 0) != 0) return {};
    const auto on = comment.rfind(" on ");
    if (on == std::string_view::npos) return {};
    return wallClockFromText(std::string(comment.substr(on + 4)));
}

std::string wallClockOfLecroySegment(std::string_view line) {
    if (line.rfind("#1,", 0) != 0) return {};
    const std::string_view rest = line.substr(3);
    return wallClockFromText(std::string(rest.substr(0, rest.find(','))));
}

}  // namespace busdecode
