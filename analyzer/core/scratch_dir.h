#pragma once
// A directory of its own under the system's temporary directory, removed with
// everything in it when the object goes: scratch space for the tests and benchmarks
// that write captures.
#include <string>

#include <sys/types.h>

namespace busdecode {

class ScratchDir {
public:
    // "<tmp>/<prefix>-" and six characters that make the name unique (mkdtemp(3)).
    // `keep`: left in place at the end, to look at its files. Throws std::runtime_error
    // when it cannot be made.
    explicit ScratchDir(const std::string& prefix, bool keep = false);
    // Removes the directory (unless kept), and only in the process that made it: a
    // forked child that exits normally must not take it from its parent.
    ~ScratchDir();
    ScratchDir(const ScratchDir&) = delete;
    ScratchDir& operator=(const ScratchDir&) = delete;

    const std::string& path() const { return path_; }

private:
    std::string path_;
    pid_t owner_;
    bool keep_;
};

}  // namespace busdecode
