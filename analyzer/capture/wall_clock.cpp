#include "wall_clock.h"

#include <ctime>

#include <fmt/format.h>

namespace busdecode {

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
    };
    for (const char* layout : layouts) {
        std::tm tm{};
        const char* end = strptime(s.c_str(), layout, &tm);
        if (!end || *end != '\0') continue;
        return fmt::format("{:04}-{:02}-{:02}T{:02}:{:02}:{:02}", tm.tm_year + 1900, tm.tm_mon + 1,
                           tm.tm_mday, tm.tm_hour, tm.tm_min, tm.tm_sec);
    }
    return s;
}

}  // namespace busdecode
