#include "standard_streams.h"

#include <fcntl.h>
#include <unistd.h>
#include <cerrno>
#include <cstdio>
#include <cstring>

#include <fmt/format.h>

#include "core/options.h"

namespace busdecode {

namespace {

StandardStreams g_streams;
bool g_stderr_failed = false;

// Opens /dev/null on `fd` if `fd` is closed; true if it was.
bool fillIfClosed(int fd, int flags) {
    if (::fcntl(fd, F_GETFD) != -1 || errno != EBADF) return false;
    const int placeholder = ::open("/dev/null", flags);
    // The lowest free number is fd itself (the lower ones are open or filled already).
    if (placeholder >= 0 && placeholder != fd) {
        ::dup2(placeholder, fd);
        ::close(placeholder);
    }
    return true;
}

}  // namespace

StandardStreams guardStandardStreams() {
    g_streams.stdin_closed = fillIfClosed(STDIN_FILENO, O_WRONLY);
    g_streams.stdout_closed = fillIfClosed(STDOUT_FILENO, O_RDONLY);
    fillIfClosed(STDERR_FILENO, O_RDONLY);
    return g_streams;
}

const StandardStreams& standardStreams() {
    return g_streams;
}

void printError(std::string_view text) {
    if (std::fwrite(text.data(), 1, text.size(), stderr) != text.size() || std::fflush(stderr) != 0)
        g_stderr_failed = true;
}

bool standardErrorFailed() {
    return g_stderr_failed || std::ferror(stderr);
}

void checkStandardOutput() {
    const bool flushed = std::fflush(stdout) == 0;
    const int why = errno;
    if (flushed && !std::ferror(stdout)) return;
    if (g_streams.stdout_closed) throw InputError("standard output: cannot write: it is closed");
    throw InputError(fmt::format("standard output: cannot write: {}",
                                 flushed ? "a write failed" : std::strerror(why)));
}

}  // namespace busdecode
