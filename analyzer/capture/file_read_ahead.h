#pragma once
// Reads a regular file ahead on a thread of its own, into a ring of chunks that the
// TextSource then scans in place. The kernel's copy out of the page cache (a fifth of
// reading a cached VCD) then runs on whichever core has time for it, not on the
// tokenising thread: on a busy SPI bus, the decoding thread's core while it waits for
// edges (bench/README.md, "The file read on a thread of its own").
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace busdecode {

class FileReadAhead {
public:
    // Bytes per chunk, and the room kept free before each chunk's bytes: the unread
    // tail of the chunk before (a line cut by the chunk's end) is copied there, so that
    // the line reads whole.
    static constexpr std::size_t kChunkBytes = 1 << 20;
    static constexpr std::size_t kHeadroom = 4096;
    static constexpr std::size_t kChunks = 8;

    // Reads `fd` (a regular file, not followed) from its current offset; `name` names it
    // in a read error.
    FileReadAhead(int fd, std::string name);
    ~FileReadAhead();
    FileReadAhead(const FileReadAhead&) = delete;
    FileReadAhead& operator=(const FileReadAhead&) = delete;

    struct Chunk {
        char* data = nullptr;  // kHeadroom writable bytes before it
        std::size_t size = 0;  // 0: the end of the file
    };
    // The next chunk in file order, once it is read; throws InputError on a read error.
    // The two chunks handed out last stay valid (their bytes are not overwritten).
    Chunk next();

private:
    void run();

    int fd_;
    std::string name_;
    std::vector<std::unique_ptr<char[]>> memory_;  // kChunks x (kHeadroom + kChunkBytes)
    std::vector<std::size_t> size_;
    std::mutex m_;
    std::condition_variable ready_, space_;
    std::uint64_t read_ = 0;    // chunks read (the end of the file counts as one)
    std::uint64_t handed_ = 0;  // chunks handed out by next()
    bool done_ = false;         // the reader has read the end, or failed
    bool quit_ = false;
    bool reader_waiting_ = false;
    bool consumer_waiting_ = false;
    std::string error_;
    std::thread thread_;
};

}  // namespace busdecode
