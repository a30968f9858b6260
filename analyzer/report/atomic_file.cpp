#include "atomic_file.h"

#include <cerrno>
#include <cstdio>
#include <cstring>

#include <unistd.h>

#include <fmt/format.h>

#include "core/options.h"

namespace busdecode {

void writeFileAtomically(const std::string& path, const std::string& text) {
    // Same directory as the target, so rename() stays within one file system. The pid
    // keeps parallel writers of different targets from sharing a temporary name.
    const std::string tmp = fmt::format("{}.tmp{}", path, ::getpid());
    std::FILE* f = std::fopen(tmp.c_str(), "wb");
    if (!f) throw InputError(fmt::format("{}: cannot write: {}", path, std::strerror(errno)));
    const bool wrote = std::fwrite(text.data(), 1, text.size(), f) == text.size();
    const bool flushed = std::fflush(f) == 0 && ::fsync(::fileno(f)) == 0;
    const bool closed = std::fclose(f) == 0;
    if (!wrote || !flushed || !closed) {
        const int err = errno;
        std::remove(tmp.c_str());
        throw InputError(fmt::format("{}: cannot write: {}", path, std::strerror(err)));
    }
    if (std::rename(tmp.c_str(), path.c_str()) != 0) {
        const int err = errno;
        std::remove(tmp.c_str());
        throw InputError(fmt::format("{}: cannot write: {}", path, std::strerror(err)));
    }
}

}  // namespace busdecode
