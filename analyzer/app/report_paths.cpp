#include "report_paths.h"

#include <sys/stat.h>
#include <set>

#include <fmt/format.h>

#include "core/options.h"

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
    if (captures.size() <= 1) return std::vector<std::string>(captures.size(), report);
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

void refuseOutputOnCapture(const std::string& option, const std::string& output,
                           const std::vector<std::string>& captures) {
    struct stat out {};
    if (::stat(output.c_str(), &out) != 0 || !S_ISREG(out.st_mode)) return;
    for (const auto& capture : captures) {
        struct stat in {};
        if (capture != "-" && ::stat(capture.c_str(), &in) == 0 && in.st_dev == out.st_dev &&
            in.st_ino == out.st_ino)
            throw InputError(
                fmt::format("{} {}: is the capture {}, not an output", option, output, capture));
    }
}

}  // namespace busdecode
