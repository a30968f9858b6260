#pragma once
// Complete lines of a text capture, scanned in place with memchr: standard input, pipes
// and followed files are read into one reusable buffer; other files too, or, with
// OpenOptions::read_file_ahead, past their first read, into the chunks a thread of their
// own reads ahead (FileReadAhead). Memory stays flat whatever the file size: the buffer
// only grows to the longest line, and the chunks are a ring of 8 MB.
#include <cstdint>
#include <cstring>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "capture_reader.h"

namespace busdecode {

class FileReadAhead;

class TextSource {
public:
    // Longest line accepted: a longer one is not a text capture (or is broken).
    static constexpr std::size_t kMaxLine = 1 << 20;

    // Opens `path` ("-" = standard input). Throws InputError naming the file.
    TextSource(const std::string& path, const OpenOptions& opts);
    // Reads `fd` (a pipe: decompressed input), which it closes; `name` is for messages.
    TextSource(int fd, std::string name, const OpenOptions& opts);
    ~TextSource();
    TextSource(const TextSource&) = delete;
    TextSource& operator=(const TextSource&) = delete;

    const std::string& name() const { return name_; }  // for messages: path or "<stdin>"

    enum class Status { Line, Eof, NoData };
    // Next complete line (without "\n" or "\r\n"); the view stays valid until the next
    // call. NoData: nothing complete yet on a pipe or a followed file (try again after
    // waitForData()). Eof: the end (a last line without newline is returned first).
    Status nextLine(std::string_view& line) {
        const char* nl =
            static_cast<const char*>(std::memchr(pos_, '\n', std::size_t(end_ - pos_)));
        if (nl && std::size_t(nl - pos_) <= kMaxLine) {
            line = trimCr(pos_, nl);
            pos_ = nl + 1;
            ++line_no_;
            return Status::Line;
        }
        return slowNextLine(line);
    }
    // Bulk form for byte-level scanners: the next run of complete lines, newlines
    // included (at most kMaxLine + 1 bytes; the last line of the input may lack its
    // newline). The caller counts lines from then on: lineNo() is not advanced, and
    // `first_line` (the number of the run's first line) only names a line that is too
    // long. Statuses and the view's lifetime are those of nextLine().
    Status nextLines(std::string_view& text, std::uint64_t first_line);
    // Bulk form for binary input (a compressed stream): everything buffered, refilled
    // when empty. Statuses and the view's lifetime are those of nextLine().
    Status nextBytes(std::string_view& bytes);
    // Skips the complete lines already buffered that repeat `line`, the line nextLine()
    // just returned, byte for byte with its line end ("\n" or "\r\n"), up to the first
    // other one, and returns how many: a dense CSV repeats its last row for most samples.
    // Counts them as lines returned; never reads or blocks (0 when the next line differs
    // or is not buffered whole, or `line` is not the one just returned with its newline).
    std::uint64_t skipLinesEqualTo(std::string_view line) {
        // The line as it is in the buffer: from its start to where nextLine() left pos_.
        const char* const raw = line.data();
        const auto at = reinterpret_cast<std::uintptr_t>(raw);
        if (at < reinterpret_cast<std::uintptr_t>(base_) ||
            at >= reinterpret_cast<std::uintptr_t>(pos_))
            return 0;
        const std::size_t len = std::size_t(pos_ - raw);
        if (len < line.size() + 1 || len > line.size() + 2 || pos_[-1] != '\n') return 0;
        const char* p = pos_;
        if (len <= 8) {
            // One 8-byte load per line: its first len bytes against the line.
            std::uint64_t want = 0;
            std::memcpy(&want, raw, len);
            const std::uint64_t mask = len == 8 ? ~0ULL : (1ULL << (8 * len)) - 1;
            for (std::uint64_t w; end_ - p >= 8; p += len) {
                std::memcpy(&w, p, 8);
                if ((w & mask) != want) break;
            }
        } else {
            for (; std::size_t(end_ - p) >= len; p += len)
                if (std::memcmp(p, raw, len) != 0) break;
        }
        const auto n = std::uint64_t(p - pos_) / len;
        pos_ = p;
        line_no_ += n;
        return n;
    }
    // 1-based number of the line last returned.
    std::uint64_t lineNo() const { return line_no_; }
    // Blocks up to `ms` milliseconds for more input (pipes, followed files).
    void waitForData(int ms);

    // The first bytes of the input (up to n, fewer at the end), for sniffing the format.
    std::string_view peek(std::size_t n);

    // Writes everything not yet consumed, up to the end of the input, to `out_fd`
    // (a seekable copy of standard input for formats that need one).
    void drainTo(int out_fd);

    // A regular file named on the command line (not standard input, whose offset need
    // not start at 0; not a pipe), not followed: one that can be read at any offset with
    // pread() (SegmentedVcdReader).
    bool seekable() const { return !pipe_ && !opts_.follow && fd_ != 0; }
    int fd() const { return fd_; }
    // Reads on the caller's thread only, never with a FileReadAhead: for a reader that
    // reads the body itself, on threads of its own.
    void keepReadsOnThisThread() { read_file_ahead_ = false; }
    // Drops what is buffered and goes on from `offset` of a seekable() file (a line
    // start): nextLine() and nextLines() read from there.
    void restartAt(std::uint64_t offset);

    std::uint64_t bytesRead() const { return consumed_base_ + std::uint64_t(pos_ - base_); }
    std::uint64_t bytesTotal() const { return total_; }

    // A message "NAME:LINE: what" for the line last returned.
    std::string at(const std::string& what) const;
    std::string at(std::uint64_t line, const std::string& what) const;

private:
    static std::string_view trimCr(const char* b, const char* e) {
        if (e > b && e[-1] == '\r') --e;
        return std::string_view(b, std::size_t(e - b));
    }
    void setUp();  // after fd_ is open: the file's kind, size and buffer
    Status slowNextLine(std::string_view& line);
    // No newline in what is buffered: read more (nullopt: refilled, scan again; NoData
    // on live input for now), or hand out the input's last line, which has no newline
    // (Line, in `rest`), or Eof.
    std::optional<Status> noNewline(std::string_view& rest);
    // Reads more into the buffer; returns bytes added (0 = nothing now or at the end).
    std::size_t fill();
    // fill() from the read-ahead's next chunk: the unread tail moves in front of it.
    std::size_t fillFromChunk();
    bool stopRequested() const;
    // Throws Interrupted when stopped reading a capture that is not followed.
    void throwIfInterrupted() const;
    // The input ended: an InputError if a regular file ended short of its size at open.
    void endOfFile();
    void skipByteOrderMark();

    std::string name_;
    OpenOptions opts_;
    int fd_ = -1;
    bool eof_ = false;   // the stream ended (not for followed files)
    bool pipe_ = false;  // not a regular file
    char* buf_ = nullptr;
    std::size_t cap_ = 0;
    const char* base_ = nullptr;  // start of the valid data
    const char* pos_ = nullptr;
    const char* end_ = nullptr;
    std::uint64_t consumed_base_ = 0;  // file offset of base_
    std::uint64_t file_off_ = 0;       // bytes read from the fd so far
    std::uint64_t total_ = 0;
    std::uint64_t line_no_ = 0;
    // A regular file read ahead on its own thread (OpenOptions::read_file_ahead): the
    // data is then in its chunks, or in carry_ when a tail did not fit the headroom.
    bool read_file_ahead_ = false;  // start ahead_ at the second read
    std::unique_ptr<FileReadAhead> ahead_;
    std::vector<char> carry_, spare_carry_;
};

}  // namespace busdecode
