#include "shard.h"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>

#include <fmt/format.h>

#include "core/options.h"

namespace busdecode {

std::string Shard::text() const {
    return fmt::format("{}/{}", index, count);
}

Shard parseShard(const std::string& text, const std::string& option) {
    const auto slash = text.find('/');
    const auto k = slash == std::string::npos ? std::nullopt : parseInteger(text.substr(0, slash));
    const auto n = slash == std::string::npos ? std::nullopt : parseInteger(text.substr(slash + 1));
    if (!k || !n || *n < 1 || *k < 1 || *k > *n)
        throw InputError(
            fmt::format("{} {}: expected K/N with 1 <= K <= N (K counts from 1)", option, text));
    return {std::size_t(*k), std::size_t(*n)};
}

std::pair<std::size_t, std::size_t> shardRange(std::size_t total, const Shard& shard) {
    return {total * (shard.index - 1) / shard.count, total * shard.index / shard.count};
}

std::vector<std::string> shardOf(const std::vector<std::string>& captures, const Shard& shard) {
    const auto [first, last] = shardRange(captures.size(), shard);
    return {captures.begin() + std::ptrdiff_t(first), captures.begin() + std::ptrdiff_t(last)};
}

std::vector<std::string> readCaptureList(const std::string& path) {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec))
        throw InputError(fmt::format("{}: is a directory, not a list of captures", path));
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(fmt::format("{}: cannot open: {}", path, std::strerror(errno)));
    std::vector<std::string> out;
    std::string line;
    for (std::size_t number = 1; std::getline(in, line); ++number) {
        if (!line.empty() && line.back() == '\r') line.pop_back();
        if (number == 1 && line.rfind("\xEF\xBB\xBF", 0) == 0) line.erase(0, 3);  // Windows' BOM
        if (line.find('\0') != std::string::npos)
            throw InputError(fmt::format("{}:{}: a NUL byte in a capture path", path, number));
        if (line.empty() || line[0] == '#') continue;
        out.push_back(line);
    }
    if (in.bad()) throw InputError(fmt::format("{}: cannot read: {}", path, std::strerror(errno)));
    return out;
}

}  // namespace busdecode
