#pragma once
// A fuzz input as a file: an anonymous in-memory file (memfd pages, no disk), named by
// its /proc/self/fd path. A regular file: readers may pread() it and read it in pieces.
#include <sys/mman.h>
#include <unistd.h>

#include <stdexcept>
#include <string>

namespace busdecode::fuzz {

class MemFile {
public:
    explicit MemFile(const std::string& bytes) {
        fd_ = memfd_create("busdecode-fuzz", 0);
        if (fd_ < 0) throw std::runtime_error("memfd_create failed");
        std::size_t done = 0;
        while (done < bytes.size()) {
            ssize_t n = write(fd_, bytes.data() + done, bytes.size() - done);
            if (n <= 0) {
                close(fd_);
                throw std::runtime_error("write to memfd failed");
            }
            done += std::size_t(n);
        }
        path_ = "/proc/self/fd/" + std::to_string(fd_);
    }
    ~MemFile() { close(fd_); }
    MemFile(const MemFile&) = delete;
    MemFile& operator=(const MemFile&) = delete;
    const std::string& path() const { return path_; }

private:
    int fd_ = -1;
    std::string path_;
};

}  // namespace busdecode::fuzz
