#include "atomic_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#include <cerrno>
#include <cstring>

#include <fmt/format.h>

#include "options.h"

namespace busdecode {

namespace {

[[noreturn]] void cannotWrite(const std::string& path, int why) {
    throw InputError(fmt::format("{}: cannot write: {}", path, std::strerror(why)));
}

// What is at `path` now: a regular file's mode, none, or something not to be replaced
// (a device such as /dev/null, a FIFO, a symlink such as /dev/stdout, a socket).
enum class Target { New, Regular, Through };
Target targetOf(const std::string& path, mode_t& mode) {
    struct stat st {};
    if (::lstat(path.c_str(), &st) != 0) return Target::New;
    if (S_ISDIR(st.st_mode))
        throw InputError(fmt::format("{}: cannot write: is a directory", path));
    mode = st.st_mode & 07777;
    return S_ISREG(st.st_mode) ? Target::Regular : Target::Through;
}

}  // namespace

AtomicFile::AtomicFile(const std::string& path) : path_(path) {
    mode_t mode = 0;
    const Target target = targetOf(path, mode);
    int fd;
    if (target == Target::Through) {
        through_ = true;
        fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
        if (fd < 0) cannotWrite(path, errno);
    } else {
        // Same directory as the target, so rename() stays within one file system.
        tmp_ = path + ".tmp-XXXXXX";
        fd = mkstemp(tmp_.data());
        if (fd < 0) cannotWrite(path, errno);
        // mkstemp creates the file 0600: an ordinary new output file, or the mode of the
        // file it replaces.
        if (target == Target::New) {
            const mode_t mask = umask(0);
            umask(mask);
            mode = 0666 & ~mask;
        }
        fchmod(fd, mode);
    }
    f_ = fdopen(fd, "w");
    if (!f_) {
        const int why = errno;
        close(fd);
        if (!through_) unlink(tmp_.c_str());
        cannotWrite(path, why);
    }
    std::setvbuf(f_, nullptr, _IOFBF, 1 << 20);
}

AtomicFile::~AtomicFile() {
    if (f_) {
        std::fclose(f_);
        if (!through_) unlink(tmp_.c_str());
    }
}

void AtomicFile::commit() {
    // fsync() only for the file renamed into place: a pipe or a device has nothing to sync.
    const bool ok =
        std::fflush(f_) == 0 && std::ferror(f_) == 0 && (through_ || ::fsync(::fileno(f_)) == 0);
    int why = errno;
    const bool closed = std::fclose(f_) == 0;
    if (ok && !closed) why = errno;
    f_ = nullptr;
    if (through_) {
        if (!ok || !closed) cannotWrite(path_, why);
        return;
    }
    if (ok && closed && std::rename(tmp_.c_str(), path_.c_str()) == 0) return;
    if (ok && closed) why = errno;
    unlink(tmp_.c_str());
    cannotWrite(path_, why);
}

void checkWritable(const std::string& path) {
    mode_t mode = 0;
    if (targetOf(path, mode) == Target::Through) {
        // Not opened now: a FIFO's reader would see an end of file before the output.
        if (::access(path.c_str(), W_OK) != 0 && errno != ENOENT) cannotWrite(path, errno);
        return;
    }
    AtomicFile probe(path);  // removed again without commit()
}

void writeFileAtomically(const std::string& path, std::string_view text) {
    AtomicFile out(path);
    out.put(text);
    out.commit();
}

}  // namespace busdecode
