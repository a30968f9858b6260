#include "live_save.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

#include <fmt/format.h>

#include "capture_writer.h"
#include "core/atomic_file.h"
#include "core/options.h"

namespace busdecode {

LiveSaver::LiveSaver(std::string path, std::vector<std::string> names, std::uint64_t samplerate)
    : path_(std::move(path)),
      names_(std::move(names)),
      rate_(samplerate),
      unit_(unsigned((names_.size() + 7) / 8)) {
    // A session is a ZIP renamed into place: a device or FIFO cannot hold one.
    struct stat st {};
    if (stat(path_.c_str(), &st) == 0 && !S_ISREG(st.st_mode))
        throw InputError(fmt::format("--save {}: not a regular file", path_));
    checkWritable(path_);
    std::string spool = path_ + ".spool-XXXXXX";
    const int fd = mkstemp(spool.data());
    if (fd < 0)
        throw InputError(fmt::format("--save {}: cannot write: {}", path_, std::strerror(errno)));
    unlink(spool.c_str());  // gone with the process, whatever ends it
    spool_ = fdopen(fd, "w+b");
    if (!spool_) {
        close(fd);
        throw InputError(fmt::format("--save {}: cannot write: {}", path_, std::strerror(errno)));
    }
}

LiveSaver::~LiveSaver() {
    if (spool_) std::fclose(spool_);
}

void LiveSaver::add(const std::uint8_t* data, std::size_t n, unsigned unit) {
    if (unit != unit_) {
        // Words wider than the enabled lines need: the low bytes hold them.
        repacked_.assign(n * unit_, 0);
        for (std::size_t i = 0; i < n; ++i)
            std::memcpy(&repacked_[i * unit_], data + i * unit, std::min(unit, unit_));
        data = repacked_.data();
    }
    std::fwrite(data, unit_, n, spool_);
    samples_ += n;
}

bool LiveSaver::finish() {
    if (std::fflush(spool_) != 0 || std::ferror(spool_))
        throw InputError(fmt::format("--save {}: cannot write: {}", path_, std::strerror(errno)));
    if (samples_ == 0) return false;
    const int fd = fileno(spool_);
    const std::size_t unit = unit_;
    writeSrSamples(path_, names_, std::int64_t(rate_), samples_,
                   [&](std::uint64_t first, std::size_t n, std::uint8_t* out) {
                       std::size_t want = n * unit, got = 0;
                       while (got < want) {
                           const ssize_t r =
                               pread(fd, out + got, want - got, off_t(first * unit + got));
                           if (r <= 0)
                               throw InputError(path_ + ": cannot read the spooled samples");
                           got += std::size_t(r);
                       }
                   });
    return true;
}

}  // namespace busdecode
