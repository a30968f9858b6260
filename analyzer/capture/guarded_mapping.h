#pragma once
// A window of a regular file mapped read-only, for a reader that would otherwise copy it
// with pread(): the kernel's copy is about a tenth of decode's CPU time on a cached VCD.
//
// A mapped file can shrink under its reader (another program truncating or rewriting
// it), and a read of a page past the new end raises SIGBUS, which would kill decode
// where pread() returns short. So a mapping is registered with a process-wide SIGBUS
// handler: a fault inside a registered window maps zeros over the rest of the window,
// sets the window's flag and returns, and the read goes on over zeros. The reader checks
// the flag after reading and reads those bytes again some other way (read() reports
// what the file now holds). A SIGBUS anywhere else goes to the handler that was there
// before, or kills the process as it would have.
#include <atomic>
#include <cstddef>
#include <cstdint>

namespace busdecode {

class GuardedMapping {
public:
    GuardedMapping() = default;
    GuardedMapping(const GuardedMapping&) = delete;
    GuardedMapping& operator=(const GuardedMapping&) = delete;
    ~GuardedMapping() { unmap(); }

    // Maps bytes [from, to) of `fd` (any offsets), unmapping what was mapped before.
    // `shrunk` is set if a read of the window found the file shorter than it was. False
    // if it cannot be mapped or guarded (read the bytes another way).
    bool map(int fd, std::uint64_t from, std::uint64_t to, std::atomic<bool>* shrunk);
    void unmap();
    const char* data() const { return data_; }  // the byte at `from`

private:
    void* base_ = nullptr;  // the mapping, from `from` rounded down to a page
    std::size_t length_ = 0;
    const char* data_ = nullptr;
    int slot_ = -1;  // its entry in the SIGBUS handler's table
};

}  // namespace busdecode
