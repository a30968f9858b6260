#include "report_paths.h"

#include <sys/stat.h>
#include <set>

namespace busdecode {

namespace {

// "dir/r.txt" -> {"dir/r", ".txt"}; a dot in a directory name is not an extension.
std::pair<std::string, std::string> splitExtension(const std::string& path) {
    const auto slash = path.find_last_of('/');
    const auto dot = path.find_last_of('.');
    const std::size_t name_start = slash == std::string::npos ? 0 : slash + 1;
    if (dot == std::string::npos || dot <= name_start) return {path, ""};
    return {path.substr(0, dot), path.substr(dot)};
}

std::string fileName(const std::string& path) {
    const auto slash = path.find_last_of('/');
    return slash == std::string::npos ? path : path.substr(slash + 1);
}

}  // namespace

std::vector<std::string> reportPaths(const std::string& report,
                                     const std::vector<std::string>& captures) {
    struct stat st {};
    const bool through = ::stat(report.c_str(), &st) == 0 && !S_ISREG(st.st_mode);
    if (captures.size() <= 1 || through) return std::vector<std::string>(captures.size(), report);
    const auto [stem, ext] = splitExtension(report);
    std::vector<std::string> out;
    std::set<std::string> used;
    for (const auto& capture : captures) {
        const std::string named = stem + "-" + fileName(capture);
        std::string path = named + ext;
        for (int n = 2; used.count(path); ++n)
            path = named + "-" + std::to_string(n) + ext;
        used.insert(path);
        out.push_back(path);
    }
    return out;
}

}  // namespace busdecode
