// `decode -` (standard input) with --follow: a writer feeds a capture through a pipe in
// pieces with pauses, and decoded events come out while the writer still holds back the
// rest; the whole output then equals decoding the complete file.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

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

TEST(FollowPipe, EventsComeOutBeforeTheWriterFinishes) {
    const std::string text = "Hello, follow mode! The quick brown fox jumps.";
    const std::size_t split = 20;
    test::UartVcd vcd = test::uartVcd(text, split);
    const std::vector<std::string> decode_args{"--proto",    "uart",     "--opt",
                                               "baud=10000", "--format", "jsonl"};

    std::vector<std::string> args{"-", "--follow"};
    args.insert(args.end(), decode_args.begin(), decode_args.end());
    ::signal(SIGPIPE, SIG_IGN);
    test::DecodeProcess c = test::spawnDecode(args);
    ASSERT_GT(c.pid, 0);
    // The first part in pieces of 97 bytes (cutting lines anywhere), with pauses.
    for (std::size_t at = 0; at < vcd.head.size(); at += 97) {
        ASSERT_TRUE(test::writeAll(c.in, vcd.head.substr(at, 97)));
        std::this_thread::sleep_for(5ms);
    }
    // The writer now waits: the bytes of the first part must come out meanwhile.
    std::string out;
    std::size_t early = readLines(c.out, out, split, 20s);
    EXPECT_EQ(early, split) << "events decoded while the writer had not finished:\n" << out;

    for (std::size_t at = 0; at < vcd.tail.size(); at += 97) {
        ASSERT_TRUE(test::writeAll(c.in, vcd.tail.substr(at, 97)));
        std::this_thread::sleep_for(2ms);
    }
    ::close(c.in);
    readLines(c.out, out, text.size() + 1000, 20s);  // until end of output
    ::close(c.out);
    int st = 0;
    ASSERT_EQ(::waitpid(c.pid, &st, 0), c.pid);
    ASSERT_TRUE(WIFEXITED(st));
    EXPECT_EQ(WEXITSTATUS(st), 0);

    // Every byte, in order, and the same output as decoding the whole file at once.
    std::string path = test::tempDir() + "/follow_uart.vcd";
    test::writeFile(path, vcd.head + vcd.tail);
    std::vector<std::string> file_args{path};
    file_args.insert(file_args.end(), decode_args.begin(), decode_args.end());
    test::RunResult whole = test::runDecode(file_args);
    ASSERT_EQ(whole.status, 0) << whole.err;
    EXPECT_EQ(out, whole.out);
    std::size_t lines = std::size_t(std::count(out.begin(), out.end(), '\n'));
    EXPECT_EQ(lines, text.size());
    for (std::size_t i = 0; i < text.size(); ++i) {
        std::string value =
            "\"value\":" + std::to_string(static_cast<unsigned char>(text[i])) + ",";
        EXPECT_NE(out.find(value), std::string::npos) << "byte " << i;
    }
}

}  // namespace
}  // namespace busdecode
