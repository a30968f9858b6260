// A mapped window of a file (GuardedMapping) reads the file's bytes; once the file
// shrinks, the window's pages past the new end read as zeros and say so, where an
// unguarded mapping raises SIGBUS; a SIGBUS outside any window still ends the process.
#include <gtest/gtest.h>

#include <atomic>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <string>

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/wait.h>
#include <unistd.h>

#include "capture/guarded_mapping.h"
#include "capture_util.h"

namespace busdecode::test {
namespace {

std::string bytesOfLength(std::size_t n) {
    std::string s(n, '\0');
    for (std::size_t i = 0; i < n; ++i)
        s[i] = char('a' + i % 23);
    return s;
}

struct OpenFile {
    explicit OpenFile(const std::string& path) : fd(::open(path.c_str(), O_RDONLY)) {}
    ~OpenFile() {
        if (fd >= 0) ::close(fd);
    }
    int fd;
};

TEST(GuardedMapping, MapsAnyWindowOfAFile) {
    const long page = ::sysconf(_SC_PAGESIZE);
    const std::string text = bytesOfLength(std::size_t(5 * page + 123));
    const std::string path = tempCapture("window.bin", text);
    OpenFile f(path);
    ASSERT_GE(f.fd, 0);
    std::atomic<bool> shrunk{false};
    GuardedMapping m;
    for (auto [from, to] : {std::pair<std::uint64_t, std::uint64_t>{0, 1},
                            {std::uint64_t(page - 1), std::uint64_t(page + 1)},
                            {1000, std::uint64_t(3 * page + 7)},
                            {std::uint64_t(2 * page), text.size()}}) {
        ASSERT_TRUE(m.map(f.fd, from, to, &shrunk)) << from;
        EXPECT_EQ(std::string(m.data(), to - from), text.substr(from, to - from)) << from;
    }
    m.unmap();
    EXPECT_EQ(m.data(), nullptr);
    EXPECT_FALSE(shrunk.load());
    EXPECT_FALSE(m.map(f.fd, 10, 10, &shrunk));  // nothing to map
}

TEST(GuardedMapping, PagesPastAShrunkEndReadAsZerosAndSaySo) {
    const long page = ::sysconf(_SC_PAGESIZE);
    const std::string text = bytesOfLength(std::size_t(6 * page));
    const std::string path = tempCapture("shrinks.bin", text);
    OpenFile f(path);
    ASSERT_GE(f.fd, 0);
    std::atomic<bool> shrunk{false};
    GuardedMapping m;
    const std::uint64_t from = 100, cut = std::uint64_t(2 * page + 10);
    ASSERT_TRUE(m.map(f.fd, from, text.size(), &shrunk));
    std::filesystem::resize_file(path, cut);
    std::string seen(m.data(), text.size() - from);  // every byte: no SIGBUS
    EXPECT_EQ(seen.substr(0, cut - from), text.substr(from, cut - from));
    EXPECT_EQ(seen.substr(cut - from), std::string(text.size() - cut, '\0'));
    EXPECT_TRUE(shrunk.load());  // the pages wholly past the end faulted
    m.unmap();

    // A second window of the same file, and a window whose file is whole, are mended
    // and flagged only for themselves.
    std::atomic<bool> other{false}, whole_flag{false};
    const std::string whole = tempCapture("whole.bin", text);
    OpenFile g(whole);
    GuardedMapping a, b;
    ASSERT_TRUE(a.map(f.fd, 0, std::uint64_t(4 * page), &other));
    ASSERT_TRUE(b.map(g.fd, 0, text.size(), &whole_flag));
    EXPECT_EQ(a.data()[3 * page], '\0');
    EXPECT_TRUE(other.load());
    EXPECT_EQ(std::string(b.data(), text.size()), text);
    EXPECT_FALSE(whole_flag.load());
}

TEST(GuardedMappingDeathTest, ASigbusOutsideAnyWindowStillEndsTheProcess) {
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    const long page = ::sysconf(_SC_PAGESIZE);
    // Under ASan, its own SIGBUS handler (the one before ours) reports and exits 1.
    const auto died = [](int status) {
        return (WIFSIGNALED(status) && WTERMSIG(status) == SIGBUS) ||
               (WIFEXITED(status) && WEXITSTATUS(status) != 0);
    };
    EXPECT_EXIT(
        {
            // A memory file, not one in the scratch directory: the child dies by the
            // signal, so it could not remove a directory of its own.
            const int fd = ::memfd_create("unguarded", 0);
            const std::string bytes = bytesOfLength(std::size_t(4 * page));
            if (fd < 0 || ::write(fd, bytes.data(), bytes.size()) != ssize_t(bytes.size()))
                std::_Exit(2);
            std::atomic<bool> shrunk{false};
            GuardedMapping guarded;  // the handler installed, this window not the one hit
            if (!guarded.map(fd, 0, std::uint64_t(page), &shrunk)) std::_Exit(3);
            void* raw = ::mmap(nullptr, std::size_t(4 * page), PROT_READ, MAP_PRIVATE, fd, 0);
            if (raw == MAP_FAILED) std::_Exit(4);
            if (::ftruncate(fd, page) != 0) std::_Exit(5);
            volatile char c = static_cast<const char*>(raw)[3 * page];  // SIGBUS
            (void)c;
            std::_Exit(0);
        },
        died, "");
}

}  // namespace
}  // namespace busdecode::test
