#pragma once
// fstapi in a child process of its own: fstapi trusts the lengths inside a compressed
// block, so a corrupt one can corrupt the heap (an invalid free) or ask for any amount of
// memory. The child reads the file with fstapi under an address-space limit and sends
// what it finds over a socket as framed messages; a child that dies is a message for the
// parent to turn into an InputError, never a crash of the reading process.
#include <sys/types.h>

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <string_view>

namespace busdecode {

// The child's failure to send (the parent has gone): the child then simply ends.
class ChannelClosed : public std::exception {};

// One end of the socket between parent and child: messages of a kind byte and a payload.
class ChildChannel {
public:
    explicit ChildChannel(int fd) : fd_(fd) {}
    void send(std::uint8_t kind, std::string_view payload);  // throws ChannelClosed
    // The next message; false when the other end closed (or died) first.
    bool receive(std::uint8_t& kind, std::string& payload);

private:
    int fd_;
};

// A payload built field by field (host byte order: both ends are the same program).
class PayloadWriter {
public:
    PayloadWriter& u64(std::uint64_t v) { return raw(&v, sizeof v); }
    PayloadWriter& text(std::string_view s) {
        u64(s.size());
        return raw(s.data(), s.size());
    }
    PayloadWriter& raw(const void* p, std::size_t n) {
        bytes_.append(static_cast<const char*>(p), n);
        return *this;
    }
    const std::string& bytes() const { return bytes_; }

private:
    std::string bytes_;
};

// Reads a PayloadWriter's fields back; std::out_of_range when the payload is too short.
class PayloadReader {
public:
    explicit PayloadReader(std::string_view bytes) : rest_(bytes) {}
    std::uint64_t u64();
    std::string text();
    bool done() const { return rest_.empty(); }

private:
    std::string_view take(std::size_t n);
    std::string_view rest_;
};

class FstChild {
public:
    // Forks; the child runs `body` with room for `budget` bytes of memory beyond what it
    // holds at the fork (not enforced under AddressSanitizer, whose shadow needs far more
    // address space), its standard error silenced, then ends. Throws InputError naming
    // `name` when no child can be made. `cpu_seconds` bounds its processor time: a corrupt
    // block that sends fstapi round a loop ends the child (SIGXCPU), not the reading.
    FstChild(const std::string& name, std::uint64_t budget, std::uint64_t cpu_seconds,
             const std::function<void(ChildChannel&)>& body);
    ~FstChild();  // kills the child if still running and reaps it
    FstChild(const FstChild&) = delete;
    FstChild& operator=(const FstChild&) = delete;

    ChildChannel& channel() { return channel_; }
    // After the channel closed: how the child ended ("killed by signal 11 (Segmentation
    // fault)", "exit status 1"), reaping it.
    std::string howItEnded();

private:
    int fd_ = -1;
    pid_t pid_ = -1;
    ChildChannel channel_{-1};
};

}  // namespace busdecode
