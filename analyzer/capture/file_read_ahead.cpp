#include "file_read_ahead.h"

#include <cerrno>
#include <cstring>
#include <utility>

#include <pthread.h>
#include <sched.h>
#include <unistd.h>

#include <fmt/format.h>

#include "core/options.h"

namespace busdecode {

namespace {
// Chunks the reader may fill: all but the two handed out last (next()'s promise).
constexpr std::uint64_t kFillable = FileReadAhead::kChunks - 2;
}  // namespace

FileReadAhead::FileReadAhead(int fd, std::string name)
    : fd_(fd), name_(std::move(name)), size_(kChunks, 0) {
    // Not zeroed (make_unique would write all 8 MB): a small capture touches the pages
    // of its own bytes only.
    for (std::size_t i = 0; i < kChunks; ++i)
        memory_.emplace_back(new char[kHeadroom + kChunkBytes]);
    thread_ = std::thread([this] { run(); });
}

FileReadAhead::~FileReadAhead() {
    {
        std::lock_guard<std::mutex> lock(m_);
        quit_ = true;
    }
    space_.notify_all();
    thread_.join();
}

void FileReadAhead::run() {
    pthread_setname_np(pthread_self(), "decode-file");
    // Only on a core that would otherwise idle: the reading or the decoding thread's while
    // it waits for the other. With as many busy threads as cores (BiSS-C's decoding
    // thread, and the tokeniser too whenever the two keep up), taking a share of one
    // of them slows decode (bench/README.md). A tokeniser that has nothing left to read
    // waits, and its core then runs this thread.
    sched_param idle{};
    pthread_setschedparam(pthread_self(), SCHED_IDLE, &idle);
    for (;;) {
        std::uint64_t slot;
        {
            std::unique_lock<std::mutex> lock(m_);
            if (read_ >= handed_ + kFillable && !quit_) {
                // Full: sleep until half the ring is free, one wake-up per half ring.
                reader_waiting_ = true;
                space_.wait(lock,
                            [&] { return read_ + kFillable / 2 <= handed_ + kFillable || quit_; });
                reader_waiting_ = false;
            }
            if (quit_) return;
            slot = read_ % kChunks;
        }
        char* const into = memory_[slot].get() + kHeadroom;
        std::size_t got = 0;
        std::string error;
        while (got < kChunkBytes) {
            const ssize_t n = ::read(fd_, into + got, kChunkBytes - got);
            if (n > 0) {
                got += std::size_t(n);
                continue;
            }
            if (n < 0 && errno == EINTR) continue;
            if (n < 0) error = fmt::format("{}: read error: {}", name_, std::strerror(errno));
            break;  // the end of the file (or an error)
        }
        bool wake;
        {
            std::lock_guard<std::mutex> lock(m_);
            size_[slot] = got;
            ++read_;
            if (!error.empty()) error_ = std::move(error);
            // The end: a chunk of no bytes (after this one, if it holds the last bytes).
            if (got == 0 || !error_.empty()) done_ = true;
            wake = consumer_waiting_;
        }
        if (wake) ready_.notify_one();
        if (got == 0 || !error.empty()) return;
    }
}

FileReadAhead::Chunk FileReadAhead::next() {
    std::unique_lock<std::mutex> lock(m_);
    if (read_ <= handed_ && !done_) {
        consumer_waiting_ = true;
        ready_.wait(lock, [&] { return read_ > handed_ || done_; });
        consumer_waiting_ = false;
    }
    if (read_ <= handed_) {  // nothing left: the end, or a read error
        if (!error_.empty()) throw InputError(error_);
        return {};
    }
    const std::uint64_t slot = handed_ % kChunks;
    ++handed_;
    const bool wake = reader_waiting_ && read_ + kFillable / 2 <= handed_ + kFillable;
    const Chunk c{memory_[slot].get() + kHeadroom, size_[slot]};
    lock.unlock();
    if (wake) space_.notify_one();
    return c;
}

}  // namespace busdecode
