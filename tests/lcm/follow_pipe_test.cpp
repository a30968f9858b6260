// `decode -` (standard input) with --follow: a writer feeds a capture through a pipe in
// pieces with pauses, and decoded events come out while the writer still holds back the
// rest; the whole output then equals decoding the complete file. With --threads 1 as
// well, on one thread; and `decode verify -` with --threads 1 on one thread.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include <fmt/format.h>

#include "decode_process.h"
#include "support/paths.h"
#include "uart_vcd.h"

namespace busdecode {
namespace {

using namespace std::chrono_literals;

// Reads what the child printed so far, waiting up to `timeout` for at least `min_lines`
// complete lines (or end of output).
std::size_t readLines(int fd, std::string& buf, std::size_t min_lines,
                      std::chrono::milliseconds timeout) {
    auto deadline = std::chrono::steady_clock::now() + timeout;
    auto count = [&] { return std::size_t(std::count(buf.begin(), buf.end(), '\n')); };
    while (count() < min_lines) {
        auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
            deadline - std::chrono::steady_clock::now());
        if (left.count() <= 0) break;
        pollfd p{fd, POLLIN, 0};
        if (::poll(&p, 1, int(left.count())) <= 0) break;
        char tmp[4096];
        ssize_t n = ::read(fd, tmp, sizeof tmp);
        if (n <= 0) break;
        buf.append(tmp, std::size_t(n));
    }
    return count();
}

// The threads of a running process (its entries in /proc/PID/task).
int threadsOf(pid_t pid) {
    const std::filesystem::path tasks = "/proc/" + std::to_string(pid) + "/task";
    std::error_code ec;
    int n = 0;
    for (auto it = std::filesystem::directory_iterator(tasks, ec);
         !ec && it != std::filesystem::directory_iterator(); it.increment(ec))
        ++n;
    return n;
}

struct FollowRun {
    std::size_t early = 0;  // lines out while the writer held back the second part
    int threads = 0;        // decode's threads at that moment
    int status = -1;
    bool written = true;  // every piece written to decode's standard input
    std::string out;
};

// Feeds `vcd` to `decode - --follow ARGS...` in pieces with pauses: the first part, then
// (once `split` lines came out, or 20 s passed) the rest.
FollowRun followPipe(const test::UartVcd& vcd, std::size_t split,
                     const std::vector<std::string>& decode_args) {
    FollowRun r;
    std::vector<std::string> args{"-", "--follow"};
    args.insert(args.end(), decode_args.begin(), decode_args.end());
    ::signal(SIGPIPE, SIG_IGN);
    test::DecodeProcess c = test::spawnDecode(args);
    if (c.pid <= 0) return r;
    // The first part in pieces of 97 bytes (cutting lines anywhere), with pauses.
    for (std::size_t at = 0; at < vcd.head.size(); at += 97) {
        r.written = test::writeAll(c.in, vcd.head.substr(at, 97)) && r.written;
        std::this_thread::sleep_for(5ms);
    }
    // The writer now waits: the bytes of the first part must come out meanwhile.
    r.early = readLines(c.out, r.out, split, 20s);
    r.threads = threadsOf(c.pid);
    for (std::size_t at = 0; at < vcd.tail.size(); at += 97) {
        r.written = test::writeAll(c.in, vcd.tail.substr(at, 97)) && r.written;
        std::this_thread::sleep_for(2ms);
    }
    ::close(c.in);
    readLines(c.out, r.out, std::size_t(-1), 20s);  // until end of output
    ::close(c.out);
    int st = 0;
    if (::waitpid(c.pid, &st, 0) == c.pid && WIFEXITED(st)) r.status = WEXITSTATUS(st);
    return r;
}

// decode ARGS... on the whole capture in a file.
test::RunResult decodeWhole(const test::UartVcd& vcd, const std::vector<std::string>& args) {
    std::string path = test::tempDir() + "/follow_uart.vcd";
    test::writeFile(path, vcd.head + vcd.tail);
    std::vector<std::string> file_args{path};
    file_args.insert(file_args.end(), args.begin(), args.end());
    return test::runDecode(file_args);
}

const std::vector<std::string> kDecodeArgs{"--proto",    "uart",     "--opt",
                                           "baud=10000", "--format", "jsonl"};

TEST(FollowPipe, EventsComeOutBeforeTheWriterFinishes) {
    const std::string text = "Hello, follow mode! The quick brown fox jumps.";
    const std::size_t split = 20;
    test::UartVcd vcd = test::uartVcd(text, split);
    FollowRun r = followPipe(vcd, split, kDecodeArgs);
    EXPECT_TRUE(r.written);
    EXPECT_EQ(r.early, split) << "events decoded while the writer had not finished:\n" << r.out;
    EXPECT_EQ(r.threads, 2) << "reading ahead on a second thread";
    EXPECT_EQ(r.status, 0);

    // Every byte, in order, and the same output as decoding the whole file at once.
    test::RunResult whole = decodeWhole(vcd, kDecodeArgs);
    ASSERT_EQ(whole.status, 0) << whole.err;
    EXPECT_EQ(r.out, whole.out);
    std::size_t lines = std::size_t(std::count(r.out.begin(), r.out.end(), '\n'));
    EXPECT_EQ(lines, text.size());
    for (std::size_t i = 0; i < text.size(); ++i) {
        std::string value =
            "\"value\":" + std::to_string(static_cast<unsigned char>(text[i])) + ",";
        EXPECT_NE(r.out.find(value), std::string::npos) << "byte " << i;
    }
}

// --threads 1: the same events, as promptly, read on the decoding thread alone.
TEST(FollowPipe, ThreadsOneReadsAndDecodesOnOneThread) {
    const std::string text = "One thread reads and decodes.";
    const std::size_t split = 12;
    test::UartVcd vcd = test::uartVcd(text, split);
    std::vector<std::string> args = kDecodeArgs;
    args.insert(args.end(), {"--threads", "1"});
    FollowRun r = followPipe(vcd, split, args);
    EXPECT_TRUE(r.written);
    EXPECT_EQ(r.early, split) << r.out;
    EXPECT_EQ(r.threads, 1);
    EXPECT_EQ(r.status, 0);
    test::RunResult whole = decodeWhole(vcd, kDecodeArgs);
    ASSERT_EQ(whole.status, 0) << whole.err;
    EXPECT_EQ(r.out, whole.out);
    EXPECT_EQ(std::size_t(std::count(r.out.begin(), r.out.end(), '\n')), text.size());
}

// `text` as a PicoScope CSV of one analog line "A" (8N1, 10000 baud, 0 and 3.3 V sampled
// every 10 us, a byte every 1.5 ms), split in the idle time after byte `split_after`.
test::UartVcd uartScopeCsv(const std::string& text, std::size_t split_after) {
    test::UartVcd csv{"Time,Channel A\n(ms),(V)\n\n", ""};
    auto level = [&](double ms) {
        const double since = ms - 1.0;
        const int byte = int(std::floor(since / 1.5)),
                  bit = int(std::floor((since - 1.5 * byte) * 10));
        if (since < 0 || byte >= int(text.size()) || bit >= 10) return 1;
        if (bit == 0) return 0;
        if (bit == 9) return 1;
        return (static_cast<unsigned char>(text[std::size_t(byte)]) >> (bit - 1)) & 1;
    };
    const double split_ms = 1.0 + 1.5 * double(split_after) - 0.2;
    for (int k = 0; k * 0.01 < 1.0 + 1.5 * double(text.size()) + 1.0; ++k) {
        const double ms = k * 0.01;
        const std::string row = fmt::format("{:.2f},{:.3f}\n", ms, level(ms + 0.005) ? 3.3 : 0.0);
        (ms < split_ms ? csv.head : csv.tail) += row;
    }
    return csv;
}

// A scope CSV followed through a pipe: its levels are found from the rows there are when
// the writer pauses, and the bytes come out while it waits, as from a logic capture.
TEST(FollowPipe, AScopeCsvDecodesWhileTheWriterWaits) {
    const std::string text = "Scope rows, followed.";
    const std::size_t split = 12;
    const test::UartVcd csv = uartScopeCsv(text, split);
    const std::vector<std::string> args{"--proto", "uart",       "--map",    "rx=A",
                                        "--opt",   "baud=10000", "--format", "jsonl"};
    FollowRun r = followPipe(csv, split, args);
    EXPECT_TRUE(r.written);
    EXPECT_EQ(r.early, split) << r.out;
    EXPECT_EQ(r.status, 0);
    const std::string path = test::tempDir() + "/follow_uart_scope.csv";
    test::writeFile(path, csv.head + csv.tail);
    std::vector<std::string> whole_args{path};
    whole_args.insert(whole_args.end(), args.begin(), args.end());
    const test::RunResult whole = test::runDecode(whole_args);
    ASSERT_EQ(whole.status, 0) << whole.err;
    std::size_t bytes = 0;
    for (std::size_t i = 0; i < text.size(); ++i) {
        const std::string value =
            "\"value\":" + std::to_string(static_cast<unsigned char>(text[i])) + ",";
        EXPECT_NE(r.out.find(value), std::string::npos) << "byte " << i << "\n" << r.out;
        bytes += whole.out.find(value) != std::string::npos;
    }
    EXPECT_EQ(bytes, text.size()) << whole.out;
}

// `decode verify -` reads its capture through a pipe as well; it prints only at the end,
// so its threads are watched while the first part waits for the rest (a reader thread
// starts as soon as the header is read): the most seen once `at_least` are and no more
// came for 0.5 s, or after 20 s. A busy machine may start them late, not fewer.
int mostThreadsOfVerify(const test::UartVcd& vcd, const std::string& threads, int& status,
                        int at_least = 0) {
    const std::string rules = test::tempDir() + "/uart_rules.toml";
    test::writeFile(rules, "[uart]\nmin_frames = 1\n");
    ::signal(SIGPIPE, SIG_IGN);
    test::DecodeProcess c = test::spawnDecode({"verify", "-", "--rules", rules, "--proto", "uart",
                                               "--opt", "baud=10000", "--threads", threads});
    if (c.pid <= 0) return 0;
    test::writeAll(c.in, vcd.head);
    int most = 0;
    const auto begun = std::chrono::steady_clock::now();
    auto last_rise = begun;
    for (auto now = begun; now < begun + 20s; now = std::chrono::steady_clock::now()) {
        if (const int n = threadsOf(c.pid); n > most) {
            most = n;
            last_rise = now;
        }
        if (most >= at_least && now - last_rise >= 500ms) break;
        std::this_thread::sleep_for(5ms);
    }
    test::writeAll(c.in, vcd.tail);
    ::close(c.in);
    std::string out;
    readLines(c.out, out, std::size_t(-1), 20s);  // until end of output
    ::close(c.out);
    int st = 0;
    status = ::waitpid(c.pid, &st, 0) == c.pid && WIFEXITED(st) ? WEXITSTATUS(st) : -1;
    return most;
}

// verify --threads 1: each capture read and decoded on one thread, one thread fewer
// than by default (the reader's); verify's own workers come on top of both.
TEST(FollowPipe, VerifyThreadsOneReadsAndDecodesOnOneThread) {
    const test::UartVcd vcd = test::uartVcd("Verified on one thread.", 10);
    int status = -1;
    const int one = mostThreadsOfVerify(vcd, "1", status);
    EXPECT_EQ(status, 0);
    const int two = mostThreadsOfVerify(vcd, "2", status, one + 1);
    EXPECT_EQ(status, 0);
    EXPECT_EQ(two, one + 1);
}

}  // namespace
}  // namespace busdecode
