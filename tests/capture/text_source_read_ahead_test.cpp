// A regular file read ahead on a thread of its own (FileReadAhead, OpenOptions::
// read_file_ahead) is scanned in its chunks, a line cut by a chunk's end moved in front of
// the next chunk (or, longer than the room there, put together with it). Whatever the line
// lengths and wherever the chunks cut them, TextSource must give the same lines, line
// numbers, runs of lines, byte counts and errors as when it reads the file itself.
#include <gtest/gtest.h>

#include <chrono>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "capture/file_read_ahead.h"
#include "capture/text_source.h"
#include "capture_util.h"
#include "core/options.h"

#include <fcntl.h>
#include <unistd.h>

namespace busdecode::test {
namespace {

OpenOptions withReadAhead(bool on) {
    OpenOptions o;
    o.read_file_ahead = on;
    return o;
}

// What `read` takes out of the file, then `sep` and the byte count; or `sep` and the
// error.
template <class Read>
std::string readWith(const std::string& path, bool ahead, const char* sep, Read read) {
    std::string out;
    try {
        TextSource src(path, withReadAhead(ahead));
        read(src, out);
        out += std::string(sep) + "bytes " + std::to_string(src.bytesRead());
    } catch (const InputError& e) {
        out += std::string(sep) + "error " + e.what();
    }
    return out;
}

// Every line through nextLine(), with its number, then the byte count; or the error.
std::string byLine(const std::string& path, bool ahead) {
    return readWith(path, ahead, "", [](TextSource& src, std::string& out) {
        std::string_view line;
        while (src.nextLine(line) == TextSource::Status::Line)
            out.append(std::to_string(src.lineNo())).append(":").append(line).append("\n");
    });
}

// The runs of nextLines(), put back together; or the error.
std::string byRun(const std::string& path, bool ahead) {
    return readWith(path, ahead, "|", [](TextSource& src, std::string& out) {
        std::string_view text;
        while (src.nextLines(text, 1) == TextSource::Status::Line)
            out.append(text);
    });
}

// Lines of random lengths from 0 to `longest` bytes, some ending in CRLF.
std::string randomText(std::uint32_t seed, std::size_t bytes, std::size_t longest) {
    std::mt19937_64 rng(seed);
    std::string text;
    while (text.size() < bytes) {
        const std::size_t n = rng() % 4 == 0 ? rng() % (longest + 1) : rng() % 40;
        for (std::size_t i = 0; i < n; ++i)
            text += char('a' + rng() % 26);
        text += rng() % 5 == 0 ? "\r\n" : "\n";
    }
    return text;
}

TEST(TextSourceReadAhead, SameLinesWhereverTheChunksCutThem) {
    const std::size_t chunk = FileReadAhead::kChunkBytes;
    struct Case {
        std::string name;
        std::string text;
    };
    std::vector<Case> cases;
    // Short lines over several chunks; lines longer than the room before a chunk (4 KiB);
    // lines of up to 300 KB, cut by chunks and put together with them.
    cases.push_back({"short", randomText(1, 3 * chunk + 77, 100)});
    cases.push_back({"past_headroom", randomText(2, 3 * chunk, 3 * FileReadAhead::kHeadroom)});
    cases.push_back({"long", randomText(3, 4 * chunk, 300'000)});
    // A file of exactly one and two chunks, and one ending without a newline.
    cases.push_back({"one_chunk", std::string(chunk - 1, 'x') + "\n"});
    cases.push_back(
        {"two_chunks", randomText(4, 2 * chunk - 1, 100).substr(0, 2 * chunk - 1) + "\n"});
    cases.push_back({"no_last_newline", randomText(5, chunk + 5000, 100) + "last line"});
    cases.push_back({"empty", ""});
    // A line of exactly 1 MiB (accepted) across a chunk's end, and one byte longer (an
    // error naming its line).
    cases.push_back({"max_line", "a\n" + std::string(TextSource::kMaxLine, 'y') + "\nb\n"});
    cases.push_back({"too_long", "a\n" + std::string(TextSource::kMaxLine + 1, 'y') + "\nb\n"});
    for (const Case& c : cases) {
        SCOPED_TRACE(c.name);
        const std::string path = tempCapture(c.name + ".txt", c.text);
        const std::string lines = byLine(path, false);
        EXPECT_EQ(byLine(path, true), lines);
        const std::string runs = byRun(path, false);
        EXPECT_EQ(byRun(path, true), runs);
        if (c.name == "too_long") {
            EXPECT_NE(lines.find(":2: line longer than 1 MiB"), std::string::npos) << lines;
        } else {
            EXPECT_EQ(runs, c.text + "|bytes " + std::to_string(c.text.size()));
        }
    }
}

TEST(TextSourceReadAhead, ACaptureReadsTheSameEitherWay) {
    // A VCD over several chunks, through its reader: the same edges, levels and end.
    std::string vcd =
        "$timescale 10 ns $end\n$scope module m $end\n$var wire 1 ! a $end\n"
        "$var wire 1 \" b $end\n$upscope $end\n$enddefinitions $end\n#0 0! 0\"\n";
    std::mt19937_64 rng(9);
    for (std::uint64_t t = 1; vcd.size() < 3 * FileReadAhead::kChunkBytes; ++t)
        vcd += "#" + std::to_string(t * 7) + (rng() % 2 ? " 1!" : " 0!") + "\n" +
               (rng() % 3 ? "1\"\n" : "0\"\n");
    const std::string path = tempCapture("chunks.vcd", vcd);
    const Collected a = collectFile(path, {}, withReadAhead(false));
    const Collected b = collectFile(path, {}, withReadAhead(true));
    ASSERT_GT(a.edges.size(), 100000u);
    EXPECT_EQ(b.edges, a.edges);
    EXPECT_EQ(b.initial, a.initial);
    EXPECT_EQ(b.end, a.end);
}

TEST(TextSourceReadAhead, TheTwoChunksHandedOutLastStayIntact) {
    // TextSource scans the chunk handed out last and copies a line's start out of the one
    // before: the reader, however far ahead, must not write into either. Chunk i of the
    // file is all byte 'a' + i; the reader is given time to fill every chunk it may.
    const std::size_t chunk = FileReadAhead::kChunkBytes;
    std::string text;
    for (int i = 0; i < 12; ++i)
        text.append(chunk, char('a' + i));
    const std::string path = tempCapture("chunks.bin", text);
    const int fd = ::open(path.c_str(), O_RDONLY);
    ASSERT_GE(fd, 0);
    {
        FileReadAhead ahead(fd, path);
        const FileReadAhead::Chunk first = ahead.next();
        const FileReadAhead::Chunk second = ahead.next();
        std::this_thread::sleep_for(std::chrono::milliseconds(300));
        ASSERT_EQ(first.size, chunk);
        ASSERT_EQ(second.size, chunk);
        EXPECT_EQ(std::string(first.data, first.size), std::string(chunk, 'a'));
        EXPECT_EQ(std::string(second.data, second.size), std::string(chunk, 'b'));
        for (int i = 2; i < 12; ++i) {
            const FileReadAhead::Chunk c = ahead.next();
            ASSERT_EQ(c.size, chunk);
            EXPECT_EQ(std::string(c.data, c.size), std::string(chunk, char('a' + i))) << i;
        }
        EXPECT_EQ(ahead.next().size, 0u);
        EXPECT_EQ(ahead.next().size, 0u);  // and stays at the end
    }
    ::close(fd);
}

}  // namespace
}  // namespace busdecode::test
