#include "scratch_dir.h"

#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <system_error>

#include <unistd.h>

namespace busdecode {

ScratchDir::ScratchDir(const std::string& prefix, bool keep) : owner_(getpid()), keep_(keep) {
    // mkdtemp(3) replaces the template's last six characters, which must be "XXXXXX".
    path_ = (std::filesystem::temp_directory_path() / (prefix + "-XXXXXX")).string();
    if (!mkdtemp(path_.data()))
        throw std::runtime_error("cannot make a scratch directory " + path_);
}

ScratchDir::~ScratchDir() {
    if (keep_ || getpid() != owner_) return;
    std::error_code ec;  // a child process may still hold a file: best effort
    std::filesystem::remove_all(path_, ec);
}

}  // namespace busdecode
