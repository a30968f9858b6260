#include "output_guard.h"

#include <sys/stat.h>

#include <filesystem>
#include <optional>
#include <system_error>

#include <fmt/format.h>

#include "app/decode_args.h"
#include "core/options.h"

namespace busdecode {

namespace {

std::optional<struct stat> statOf(const std::string& path) {
    struct stat st {};
    if (path.empty() || path == "-" || ::stat(path.c_str(), &st) != 0) return std::nullopt;
    return st;
}

bool isSpecial(const std::string& path) {
    const auto st = statOf(path);
    return st && !S_ISREG(st->st_mode);
}

// One file under two names: the same inode when both exist, else the same absolute path
// once `.`, `..` and links in the existing part are resolved.
bool sameFile(const std::string& a, const std::string& b) {
    const auto sa = statOf(a), sb = statOf(b);
    if (sa && sb) return sa->st_dev == sb->st_dev && sa->st_ino == sb->st_ino;
    if (sa || sb) return false;
    std::error_code ea, eb;
    const auto ca = std::filesystem::weakly_canonical(std::filesystem::absolute(a), ea);
    const auto cb = std::filesystem::weakly_canonical(std::filesystem::absolute(b), eb);
    return !ea && !eb && ca == cb;
}

}  // namespace

std::vector<NamedFile> runInputs(const DecodeArgs& a, const std::vector<std::string>& captures) {
    std::vector<NamedFile> inputs;
    for (const auto& c : captures)
        inputs.push_back({"capture", c});
    if (!a.rules.empty()) inputs.push_back({"rules file", a.rules});
    if (!a.from_list.empty()) inputs.push_back({"capture list", a.from_list});
    return inputs;
}

void refuseOutputOnInputs(const std::string& option, const std::string& output,
                          const std::vector<NamedFile>& inputs) {
    const auto out = statOf(output);
    if (!out || !S_ISREG(out->st_mode)) return;  // new, or a device written through
    for (const auto& input : inputs) {
        const auto in = statOf(input.path);
        if (in && in->st_dev == out->st_dev && in->st_ino == out->st_ino)
            throw InputError(fmt::format("{} {}: is the {} {}, not an output", option, output,
                                         input.what, input.path));
    }
}

void refuseSharedOutputs(const std::vector<NamedFile>& outputs) {
    for (std::size_t i = 0; i < outputs.size(); ++i)
        for (std::size_t j = 0; j < i; ++j)
            if (!isSpecial(outputs[i].path) && sameFile(outputs[i].path, outputs[j].path))
                throw InputError(fmt::format("{} {}: {} writes there too", outputs[i].what,
                                             outputs[i].path, outputs[j].what));
}

std::string lcmLogFile(const std::string& url) {
    constexpr std::string_view kFile = "file://";
    if (url.rfind(kFile, 0) != 0) return "";
    const std::string rest = url.substr(kFile.size());
    return rest.substr(0, rest.find('?'));
}

}  // namespace busdecode
