#pragma once
// Output files (captures written by the generators, reports, JUnit, logs) are written
// atomically: into a temporary file beside the target, renamed over it on commit(), so
// an interrupted run leaves the old file or the complete new one, never half of one.
// Only a regular file or a new path is replaced so: a device (/dev/null), a FIFO, a
// symlink (/dev/stdout) or a socket is opened and written through, and stays what it is.
#include <cstdio>
#include <string>
#include <string_view>

namespace busdecode {

class AtomicFile {
public:
    // Throws InputError naming the file when it cannot be created.
    explicit AtomicFile(const std::string& path);
    ~AtomicFile();  // without commit(): the temporary file is removed
    AtomicFile(const AtomicFile&) = delete;
    AtomicFile& operator=(const AtomicFile&) = delete;

    std::FILE* file() { return f_; }
    void put(std::string_view s) { std::fwrite(s.data(), 1, s.size(), f_); }
    // Flushes, closes and renames into place. Throws InputError naming the file.
    void commit();

private:
    std::string path_, tmp_;
    std::FILE* f_ = nullptr;
    bool through_ = false;  // not a regular file: written in place, never renamed over
};

// The whole text at once (reports, JUnit).
void writeFileAtomically(const std::string& path, std::string_view text);

// Throws the InputError writing `path` would throw (no such directory, no permission),
// having created and removed a temporary file beside it: an output written at the end of
// a long run is checked before the run.
void checkWritable(const std::string& path);

}  // namespace busdecode
