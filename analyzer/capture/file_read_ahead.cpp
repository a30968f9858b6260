#include "file_read_ahead.h"

#include <cerrno>
#include <condition_variable>
#include <cstring>
#include <mutex>
#include <thread>
#include <utility>
#include <vector>

#include <fcntl.h>
#include <pthread.h>
#include <sched.h>
#include <sys/resource.h>
#include <unistd.h>

#include <fmt/format.h>

#include "core/options.h"

namespace busdecode {

namespace {
// Chunks the thread may fill: all but the two handed out last (next()'s promise).
constexpr std::uint64_t kFillable = FileReadAhead::kChunks - 2;

using Buffer = std::unique_ptr<char[]>;

Buffer newBuffer() {
    // Not zeroed (make_unique would write every byte): a small capture touches the pages
    // of its own bytes only.
    return Buffer(new char[FileReadAhead::kHeadroom + FileReadAhead::kChunkBytes]);
}

struct Read {
    std::size_t size = 0;
    std::string error;
};
}  // namespace

struct FileReadAhead::Ring {
    Ring(int caller_fd, std::string file_name)
        : name(std::move(file_name)),
          origin(::lseek(caller_fd, 0, SEEK_CUR)),
          thread_fd(::fcntl(caller_fd, F_DUPFD_CLOEXEC, 0)),
          thread_spare(newBuffer()),
          caller_spare(newBuffer()),
          size(kChunks, 0) {
        for (std::size_t i = 0; i < kChunks; ++i)
            memory.push_back(newBuffer());
    }
    ~Ring() {
        if (thread_fd >= 0) ::close(thread_fd);
    }

    // Chunk `index` of `fd` read into `into` (past its headroom) with pread.
    Read readChunk(int fd, std::uint64_t index, char* into) const {
        Read r;
        const off_t at = origin + off_t(index * kChunkBytes);
        while (r.size < kChunkBytes) {
            const ssize_t n = ::pread(fd, into + r.size, kChunkBytes - r.size, at + off_t(r.size));
            if (n > 0) {
                r.size += std::size_t(n);
                continue;
            }
            if (n < 0 && errno == EINTR) continue;
            if (n < 0) r.error = fmt::format("{}: read error: {}", name, std::strerror(errno));
            break;  // the end of the file (or an error)
        }
        return r;
    }

    // Under m: `buffer` becomes chunk `index` if that chunk is still the next to publish
    // (else the other side read it first, and `buffer` is kept for another read).
    void publish(std::uint64_t index, Buffer& buffer, Read&& read) {
        if (index != published || done) return;
        const std::uint64_t slot = index % kChunks;
        memory[slot].swap(buffer);  // the slot's old bytes were handed out long ago
        size[slot] = read.size;
        ++published;
        if (!read.error.empty()) error = std::move(read.error);
        // The end: a chunk of no bytes (after this one, if it holds the last bytes).
        if (read.size == 0 || !error.empty()) done = true;
    }

    void run();

    const std::string name;
    const off_t origin;          // the file offset of chunk 0
    const int thread_fd;         // the thread's own descriptor: the caller's may be closed first
    std::vector<Buffer> memory;  // kChunks x (kHeadroom + kChunkBytes)
    Buffer thread_spare, caller_spare;  // each side reads into its own, then swaps it in
    std::vector<std::size_t> size;
    std::mutex m;
    std::condition_variable space;
    std::uint64_t published = 0;  // chunks published (the end of the file counts as one)
    std::uint64_t handed = 0;     // chunks handed out by next()
    bool done = false;            // the end is published, or a read failed
    bool quit = false;
    bool thread_waiting = false;  // for room in the ring
    std::string error;
};

void FileReadAhead::Ring::run() {
    pthread_setname_np(pthread_self(), "decode-file");
    // Mostly on a core that would otherwise idle: the reading or the decoding thread's
    // while it waits for the other. With as many busy threads as cores (BiSS-C's decoding
    // thread, and the tokeniser too whenever the two keep up), taking a share of one of
    // them slows decode (bench/README.md). Not SCHED_IDLE: on a busy machine such a thread
    // may wait seconds for a core even to end, and the process's exit waits for it.
    sched_param none{};
    pthread_setschedparam(pthread_self(), SCHED_BATCH, &none);
    setpriority(PRIO_PROCESS, pid_t(::gettid()), 19);
    for (;;) {
        std::uint64_t index;
        {
            std::unique_lock<std::mutex> lock(m);
            if (published >= handed + kFillable && !quit && !done) {
                // Full: sleep until half the ring is free, one wake-up per half ring.
                thread_waiting = true;
                space.wait(lock, [&] {
                    return published + kFillable / 2 <= handed + kFillable || quit || done;
                });
                thread_waiting = false;
            }
            if (quit || done) return;
            index = published;
        }
        Read got = readChunk(thread_fd, index, thread_spare.get() + kHeadroom);
        std::lock_guard<std::mutex> lock(m);
        publish(index, thread_spare, std::move(got));
    }
}

FileReadAhead::FileReadAhead(int fd, const std::string& name)
    : fd_(fd), ring_(std::make_shared<Ring>(fd, name)) {
    // Without a descriptor of its own (none left), next() reads every chunk itself.
    if (ring_->thread_fd >= 0) std::thread([ring = ring_] { ring->run(); }).detach();
}

FileReadAhead::~FileReadAhead() {
    {
        std::lock_guard<std::mutex> lock(ring_->m);
        ring_->quit = true;
    }
    ring_->space.notify_all();
}

FileReadAhead::Chunk FileReadAhead::next() {
    Ring& r = *ring_;
    std::unique_lock<std::mutex> lock(r.m);
    if (r.published <= r.handed && !r.done) {
        // Not read yet: read it here rather than wait for a thread that may get no core.
        const std::uint64_t index = r.published;
        lock.unlock();
        Read got = r.readChunk(fd_, index, r.caller_spare.get() + kHeadroom);
        lock.lock();
        r.publish(index, r.caller_spare, std::move(got));
    }
    if (r.published <= r.handed) {  // nothing left: the end, or a read error
        if (!r.error.empty()) throw InputError(r.error);
        return {};
    }
    const std::uint64_t slot = r.handed % kChunks;
    ++r.handed;
    const bool wake = r.thread_waiting && r.published + kFillable / 2 <= r.handed + kFillable;
    const Chunk c{r.memory[slot].get() + kHeadroom, r.size[slot]};
    lock.unlock();
    if (wake) r.space.notify_one();
    return c;
}

}  // namespace busdecode
