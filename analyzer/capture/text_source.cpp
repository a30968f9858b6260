#include "text_source.h"

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <thread>

#include <fcntl.h>
#include <poll.h>
#include <sys/stat.h>
#include <unistd.h>

#include <fmt/format.h>

#include "core/interrupted.h"
#include "core/options.h"
#include "file_read_ahead.h"

namespace busdecode {

namespace {
// Regular files too are read, not mapped: a chunk this size stays in the core's L2 cache
// from the kernel's copy to the tokeniser, and read() costs less than the page faults
// and releases of a mapping (bench/README.md).
constexpr std::size_t kInitialBuffer = 256 << 10;
}  // namespace

TextSource::TextSource(const std::string& path, const OpenOptions& opts) : opts_(opts) {
    if (path == "-") {
        name_ = "<stdin>";
        fd_ = 0;
    } else {
        name_ = path;
        // Not blocking: a FIFO without a writer would hold open() until one came, deaf to
        // Ctrl-C; its reads wait in poll() instead (fill(), waitForData()).
        fd_ = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
        if (fd_ < 0)
            throw InputError(fmt::format("{}: cannot open: {}", path, std::strerror(errno)));
        ::fcntl(fd_, F_SETFL, ::fcntl(fd_, F_GETFL) & ~O_NONBLOCK);
    }
    setUp();
}

TextSource::TextSource(int fd, std::string name, const OpenOptions& opts)
    : name_(std::move(name)), opts_(opts), fd_(fd) {
    setUp();
}

void TextSource::setUp() {
    struct stat st {};
    if (fstat(fd_, &st) != 0)
        throw InputError(fmt::format("{}: cannot read: {}", name_, std::strerror(errno)));
    if (S_ISDIR(st.st_mode))
        throw InputError(fmt::format("{}: is a directory, not a capture", name_));
    pipe_ = !S_ISREG(st.st_mode);
    if (!pipe_) total_ = std::uint64_t(st.st_size);
    if (!pipe_ && !opts_.follow) posix_fadvise(fd_, 0, 0, POSIX_FADV_SEQUENTIAL);
    read_file_ahead_ = !pipe_ && !opts_.follow && opts_.read_ahead && opts_.read_file_ahead;
    cap_ = kInitialBuffer;
    buf_ = static_cast<char*>(std::malloc(cap_));
    if (!buf_) throw std::bad_alloc();
    base_ = pos_ = end_ = buf_;
}

TextSource::~TextSource() {
    ahead_.reset();  // its thread reads fd_
    std::free(buf_);
    if (fd_ > 0) ::close(fd_);
}

std::string TextSource::at(const std::string& what) const {
    return at(line_no_, what);
}

std::string TextSource::at(std::uint64_t line, const std::string& what) const {
    return fmt::format("{}:{}: {}", name_, line, what);
}

void TextSource::restartAt(std::uint64_t offset) {
    ahead_.reset();
    read_file_ahead_ = false;
    carry_.clear();
    if (::lseek(fd_, off_t(offset), SEEK_SET) < 0)
        throw InputError(fmt::format("{}: cannot seek: {}", name_, std::strerror(errno)));
    base_ = pos_ = end_ = buf_;
    consumed_base_ = file_off_ = offset;
    eof_ = false;
}

bool TextSource::stopRequested() const {
    return opts_.stop && opts_.stop->load(std::memory_order_relaxed);
}

void TextSource::throwIfInterrupted() const {
    // A followed capture ends where it is stopped; any other was meant to be read whole.
    if (!opts_.follow && stopRequested())
        throw Interrupted(interruptedAt(name_, "", bytesRead(), total_));
}

void TextSource::endOfFile() {
    eof_ = true;
    // Read to an end short of the size it had when opened: cut while it was read.
    if (!pipe_ && !opts_.follow && file_off_ < total_)
        throw InputError(fmt::format("{}: truncated while read (ended at byte {} of {})", name_,
                                     file_off_, total_));
}

std::size_t TextSource::fillFromChunk() {
    const FileReadAhead::Chunk c = ahead_->next();
    if (c.size == 0) {
        endOfFile();  // the unread tail stays where it is: its chunk stays valid
        return 0;
    }
    const std::size_t keep = std::size_t(end_ - pos_);
    consumed_base_ += std::uint64_t(pos_ - base_);
    char* start;
    if (keep <= FileReadAhead::kHeadroom) {
        start = c.data - keep;
        std::memmove(start, pos_, keep);
    } else {
        // A long line across the chunk's start (at most kMaxLine: the callers check):
        // it and the chunk are put together in carry_ (the tail may be in carry_ now).
        spare_carry_.assign(pos_, end_);
        spare_carry_.insert(spare_carry_.end(), c.data, c.data + c.size);
        carry_.swap(spare_carry_);
        start = carry_.data();
    }
    base_ = pos_ = start;
    end_ = start + keep + c.size;
    file_off_ += c.size;
    return c.size;
}

std::size_t TextSource::fill() {
    if (eof_) return 0;
    if (ahead_) return fillFromChunk();
    // The read-ahead starts with the second read: the first (format sniffing and the
    // header) may be all there is, or all that is wanted (a .sr goes to libzip).
    if (read_file_ahead_ && file_off_ > 0 && file_off_ < total_) {
        ahead_ = std::make_unique<FileReadAhead>(fd_, name_);
        return fillFromChunk();
    }
    // Keep the unread tail, drop what was consumed.
    if (pos_ != buf_) {
        std::size_t keep = std::size_t(end_ - pos_);
        consumed_base_ += std::uint64_t(pos_ - base_);
        std::memmove(buf_, pos_, keep);
        base_ = pos_ = buf_;
        end_ = buf_ + keep;
    }
    if (std::size_t(end_ - buf_) == cap_) {
        std::size_t ncap = std::min(cap_ * 2, kMaxLine * 2 + kInitialBuffer);
        if (ncap == cap_) return 0;  // the caller reports the over-long line
        char* nb = static_cast<char*>(std::realloc(buf_, ncap));
        if (!nb) throw std::bad_alloc();
        end_ = nb + (end_ - buf_);
        buf_ = nb;
        base_ = pos_ = buf_;
        cap_ = ncap;
    }
    if (pipe_) {
        // Never block here: a live pipe hands back what it has so far.
        pollfd p{fd_, POLLIN, 0};
        if (poll(&p, 1, 0) <= 0) return 0;
    }
    for (;;) {
        ssize_t n = ::read(fd_, const_cast<char*>(end_), cap_ - std::size_t(end_ - buf_));
        if (n > 0) {
            end_ += n;
            file_off_ += std::uint64_t(n);
            return std::size_t(n);
        }
        if (n < 0 && errno == EINTR) continue;
        if (n < 0 && errno != EAGAIN)
            throw InputError(fmt::format("{}: read error: {}", name_, std::strerror(errno)));
        break;
    }
    if (opts_.follow && !pipe_) {
        struct stat st {};
        if (fstat(fd_, &st) != 0 || st.st_nlink == 0) {
            struct stat now {};
            if (::stat(name_.c_str(), &now) == 0)  // renamed over, or written anew
                throw InputError(fmt::format(
                    "{}: replaced by another file while following (only appending to it can "
                    "be followed): decode the new file on its own",
                    name_));
            throw InputError(fmt::format("{}: deleted while following", name_));
        }
        if (std::uint64_t(st.st_size) < file_off_)
            throw InputError(fmt::format("{}: truncated while following", name_));
        return 0;
    }
    endOfFile();
    return 0;
}

void TextSource::waitForData(int ms) {
    if (eof_) return;
    if (pipe_) {
        pollfd p{fd_, POLLIN, 0};
        // Short slices so a stop request is noticed quickly.
        for (int waited = 0; waited < ms && !stopRequested(); waited += 5)
            if (poll(&p, 1, 5) > 0) return;
        return;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(std::min(ms, 5)));
}

TextSource::Status TextSource::slowNextLine(std::string_view& line) {
    for (;;) {
        const char* nl =
            static_cast<const char*>(std::memchr(pos_, '\n', std::size_t(end_ - pos_)));
        std::size_t len = nl ? std::size_t(nl - pos_) : std::size_t(end_ - pos_);
        if (len > kMaxLine)
            throw InputError(at(line_no_ + 1, "line longer than 1 MiB (not a text capture?)"));
        if (nl) {
            line = trimCr(pos_, nl);
            pos_ = nl + 1;
            ++line_no_;
            return Status::Line;
        }
        std::string_view rest;
        const auto st = noNewline(rest);
        if (!st) continue;  // refilled
        if (*st == Status::Line) {
            line = trimCr(rest.data(), rest.data() + rest.size());
            ++line_no_;
        }
        return *st;
    }
}

std::optional<TextSource::Status> TextSource::noNewline(std::string_view& rest) {
    throwIfInterrupted();
    if (!eof_ && !stopRequested()) {
        if (fill() > 0) return std::nullopt;
        if (!eof_) return Status::NoData;
    }
    // The end: a last line without a newline still counts (not when a followed capture
    // is stopped: that line may be half written).
    if (pos_ < end_ && eof_) {
        rest = std::string_view(pos_, std::size_t(end_ - pos_));
        pos_ = end_;
        return Status::Line;
    }
    return Status::Eof;
}

TextSource::Status TextSource::nextBytes(std::string_view& bytes) {
    if (pos_ == end_ && fill() == 0) return eof_ || stopRequested() ? Status::Eof : Status::NoData;
    bytes = std::string_view(pos_, std::size_t(end_ - pos_));
    pos_ = end_;
    return Status::Line;
}

TextSource::Status TextSource::nextLines(std::string_view& text, std::uint64_t first_line) {
    for (;;) {
        // A run never exceeds kMaxLine + 1 bytes, so no line in it is too long; a line
        // crossing the run's end starts the next run and is checked there.
        const std::size_t window = std::min(std::size_t(end_ - pos_), kMaxLine + 1);
        const char* nl = static_cast<const char*>(memrchr(pos_, '\n', window));
        if (nl) {
            text = std::string_view(pos_, std::size_t(nl + 1 - pos_));
            pos_ = nl + 1;
            return Status::Line;
        }
        if (std::size_t(end_ - pos_) > kMaxLine)
            throw InputError(at(first_line, "line longer than 1 MiB (not a text capture?)"));
        if (const auto st = noNewline(text)) return *st;  // else refilled: scan again
    }
}

void TextSource::skipByteOrderMark() {
    // Windows tools start UTF-8 text with EF BB BF; it is not part of the first line.
    if (line_no_ != 0 || bytesRead() != 0) return;
    while (!eof_ && std::size_t(end_ - pos_) < 3 && fill() > 0) {
    }
    if (std::size_t(end_ - pos_) >= 3 && std::memcmp(pos_, "\xef\xbb\xbf", 3) == 0) pos_ += 3;
}

void TextSource::drainTo(int out_fd) {
    auto writeAll = [&](const char* p, std::size_t n) {
        while (n > 0) {
            ssize_t w = ::write(out_fd, p, n);
            if (w < 0 && errno == EINTR) continue;
            if (w <= 0)
                throw InputError(fmt::format("{}: cannot copy to a temporary file: {}", name_,
                                             std::strerror(errno)));
            p += w;
            n -= std::size_t(w);
        }
    };
    for (;;) {
        writeAll(pos_, std::size_t(end_ - pos_));
        pos_ = end_;
        throwIfInterrupted();
        if (eof_ || stopRequested()) return;
        if (fill() == 0 && !eof_) waitForData(50);
    }
}

std::string_view TextSource::peek(std::size_t n) {
    skipByteOrderMark();
    const std::size_t want = std::min<std::size_t>(n, 64);
    while (std::size_t(end_ - pos_) < n && !eof_ && !stopRequested()) {
        if (fill() > 0) continue;
        // Enough to tell the format: `want` bytes or one complete line (a live source
        // may write a short first line and then pause).
        if (eof_ || std::size_t(end_ - pos_) >= want ||
            std::memchr(pos_, '\n', std::size_t(end_ - pos_)))
            break;
        waitForData(50);
    }
    // Stopped before the first byte came, a followed capture too has nothing to decode.
    if (opts_.follow && stopRequested() && pos_ == end_)
        throw Interrupted(interruptedAt(name_, "", 0, 0));
    throwIfInterrupted();
    return std::string_view(pos_, std::min(n, std::size_t(end_ - pos_)));
}

}  // namespace busdecode
