#include "atomic_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#include <cerrno>
#include <cstring>

#include <fmt/format.h>

#include "options.h"

namespace busdecode {

AtomicFile::AtomicFile(const std::string& path) : path_(path), tmp_(path + ".tmp-XXXXXX") {
    // Same directory as the target, so rename() stays within one file system.
    int fd = mkstemp(tmp_.data());
    if (fd < 0) throw InputError(fmt::format("{}: cannot write: {}", path, std::strerror(errno)));
    // mkstemp creates the file 0600; the result is an ordinary output file.
    const mode_t mask = umask(0);
    umask(mask);
    fchmod(fd, 0666 & ~mask);
    f_ = fdopen(fd, "w");
    if (!f_) {
        const std::string why = std::strerror(errno);
        close(fd);
        unlink(tmp_.c_str());
        throw InputError(fmt::format("{}: cannot write: {}", path, why));
    }
    std::setvbuf(f_, nullptr, _IOFBF, 1 << 20);
}

AtomicFile::~AtomicFile() {
    if (f_) {
        std::fclose(f_);
        unlink(tmp_.c_str());
    }
}

void AtomicFile::commit() {
    const bool ok = std::fflush(f_) == 0 && std::ferror(f_) == 0 && ::fsync(::fileno(f_)) == 0;
    const bool closed = std::fclose(f_) == 0;
    f_ = nullptr;
    if (!ok || !closed || std::rename(tmp_.c_str(), path_.c_str()) != 0) {
        const std::string why = std::strerror(errno);
        unlink(tmp_.c_str());
        throw InputError(fmt::format("{}: cannot write: {}", path_, why));
    }
}

void checkWritable(const std::string& path) {
    AtomicFile probe(path);  // removed again without commit()
}

void writeFileAtomically(const std::string& path, std::string_view text) {
    AtomicFile out(path);
    out.put(text);
    out.commit();
}

}  // namespace busdecode
