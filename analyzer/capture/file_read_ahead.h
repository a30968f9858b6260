#pragma once
// Reads a regular file ahead on a thread of its own, into a ring of chunks that the
// TextSource then scans in place. The kernel's copy out of the page cache (a fifth of
// reading a cached VCD) then runs on whichever core has time for it, not on the
// tokenising thread: on a busy SPI bus, the decoding thread's core while it waits for
// edges (bench/README.md, "The file read on a thread of its own"). That thread runs only
// on a core that would otherwise idle; whenever next() finds its chunk not read
// yet it reads that chunk itself, so a machine busy with other work never stalls it.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

namespace busdecode {

class FileReadAhead {
public:
    // Bytes per chunk, and the room kept free before each chunk's bytes: the unread
    // tail of the chunk before (a line cut by the chunk's end) is copied there, so that
    // the line reads whole.
    static constexpr std::size_t kChunkBytes = 1 << 20;
    static constexpr std::size_t kHeadroom = 4096;
    static constexpr std::size_t kChunks = 8;

    // Reads `fd` (a regular file, not followed) from its current offset (with pread, on a
    // duplicate: `fd` is left as it was); `name` names it in a read error.
    FileReadAhead(int fd, const std::string& name);
    ~FileReadAhead();
    FileReadAhead(const FileReadAhead&) = delete;
    FileReadAhead& operator=(const FileReadAhead&) = delete;

    struct Chunk {
        char* data = nullptr;  // kHeadroom writable bytes before it
        std::size_t size = 0;  // 0: the end of the file
    };
    // The next chunk in file order, read here if the thread has not read it yet; throws
    // InputError on a read error. The two chunks handed out last stay valid (their bytes
    // are not overwritten).
    Chunk next();

private:
    // Everything the thread touches: shared with it, so that it is never waited for. A
    // thread that only runs on an idle core may not run for seconds on a busy machine;
    // it is left to end on its own (detached), with its own copy of the descriptor.
    struct Ring;
    int fd_;  // the caller's: next() reads with it
    std::shared_ptr<Ring> ring_;
};

}  // namespace busdecode
