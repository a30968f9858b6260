#pragma once
// Compressed captures (gzip, xz, zstd), recognised by their magic bytes: a thread of their
// own decompresses the raw input into a pipe while the reader reads the other end, as
// `zstdcat f | decode -` would, so any reader (VCD, CSV, a .sr copied to a temporary
// file) takes them unchanged and memory stays flat.
#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>
#include <thread>

#include "capture_reader.h"
#include "compression.h"
#include "text_source.h"

namespace busdecode {

class DecompressingInput {
public:
    // Starts decompressing what `raw` has not yet handed out.
    DecompressingInput(std::unique_ptr<TextSource> raw, Compression kind, const OpenOptions& opts);
    ~DecompressingInput();
    DecompressingInput(const DecompressingInput&) = delete;
    DecompressingInput& operator=(const DecompressingInput&) = delete;

    // The decompressed bytes, named as the compressed file (once).
    std::unique_ptr<TextSource> output();
    // Throws the stream's own error (truncated, corrupt), if it has one by now: after the
    // output ended early, that is why, not what the reader made of the shortened text.
    void throwIfBroken() const;

    const std::string& name() const { return name_; }
    Compression kind() const { return kind_; }
    std::uint64_t compressedRead() const { return raw_read_.load(std::memory_order_relaxed); }
    std::uint64_t compressedTotal() const { return raw_total_; }

private:
    void run();
    void decompress();
    // Writes all of [p, p+n) to the pipe; false when the reader has gone.
    bool put(const char* p, std::size_t n);
    // The next compressed bytes (empty at the end).
    std::string_view take();
    [[noreturn]] void fail(const std::string& what);

    std::unique_ptr<TextSource> raw_;
    Compression kind_;
    OpenOptions opts_;
    std::string name_;
    int read_fd_ = -1, write_fd_ = -1;
    std::atomic<std::uint64_t> raw_read_{0};
    std::uint64_t raw_total_ = 0;
    std::uint64_t at_ = 0;  // compressed offset of the bytes being decompressed
    mutable std::mutex mu_;
    std::string error_;
    std::thread thread_;
};

// `inner` reads `input`'s output; a next() that ends or throws because the stream is
// broken throws the stream's error instead, and progress counts compressed bytes.
std::unique_ptr<CaptureReader> decompressedReader(std::unique_ptr<CaptureReader> inner,
                                                  std::shared_ptr<DecompressingInput> input);

}  // namespace busdecode
