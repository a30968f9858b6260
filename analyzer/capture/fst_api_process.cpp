// The child process fstapi runs in (fst_api_process.h): fork, limits, framed messages.
#include "fst_api_process.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>

#include <fmt/format.h>

#include "core/options.h"

#if defined(__SANITIZE_ADDRESS__)
#define BUSDECODE_FST_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define BUSDECODE_FST_ASAN 1
#endif
#endif

// Set by the sanitizers and libFuzzer to write a crash report; the child must not.
extern "C" void __sanitizer_set_death_callback(void (*)(void)) __attribute__((weak));

namespace busdecode {

namespace {

bool writeAll(int fd, const char* p, std::size_t n) {
    while (n > 0) {
        const ssize_t w = ::send(fd, p, n, MSG_NOSIGNAL);
        if (w < 0 && errno == EINTR) continue;
        if (w <= 0) return false;
        p += w;
        n -= std::size_t(w);
    }
    return true;
}

bool readAll(int fd, char* p, std::size_t n) {
    while (n > 0) {
        const ssize_t r = ::recv(fd, p, n, 0);
        if (r < 0 && errno == EINTR) continue;
        if (r <= 0) return false;
        p += r;
        n -= std::size_t(r);
    }
    return true;
}

#ifndef BUSDECODE_FST_ASAN
// The address space the process holds now (VmSize), 0 when /proc cannot tell.
std::uint64_t addressSpaceNow() {
    std::FILE* f = std::fopen("/proc/self/status", "r");
    if (!f) return 0;
    char line[256];
    unsigned long long kb = 0;
    while (std::fgets(line, sizeof line, f))
        if (std::sscanf(line, "VmSize: %llu kB", &kb) == 1) break;
    std::fclose(f);
    return std::uint64_t(kb) * 1024;
}
#endif

// The child's setup: no crash reports of its own, no output, bounded memory. (It ends
// when the parent does: its socket closes, and sending fails without a SIGPIPE.)
void becomeChild(std::uint64_t budget, std::uint64_t cpu_seconds) {
    if (__sanitizer_set_death_callback) __sanitizer_set_death_callback(nullptr);
    for (int sig : {SIGSEGV, SIGBUS, SIGABRT, SIGFPE, SIGILL, SIGPIPE, SIGXCPU})
        ::signal(sig, sig == SIGPIPE ? SIG_IGN : SIG_DFL);
    if (const int null = ::open("/dev/null", O_WRONLY); null >= 0) {
        ::dup2(null, STDERR_FILENO);
        ::dup2(null, STDOUT_FILENO);
        ::close(null);
    }
    const rlimit cpu{rlim_t(cpu_seconds), rlim_t(cpu_seconds + 1)};
    ::setrlimit(RLIMIT_CPU, &cpu);
#ifndef BUSDECODE_FST_ASAN
    if (const std::uint64_t now = addressSpaceNow(); now > 0) {
        const rlimit limit{rlim_t(now + budget), rlim_t(now + budget)};
        ::setrlimit(RLIMIT_AS, &limit);
    }
#else
    (void)budget;
#endif
}

}  // namespace

void ChildChannel::send(std::uint8_t kind, std::string_view payload) {
    char head[9];
    head[0] = char(kind);
    const std::uint64_t n = payload.size();
    std::memcpy(head + 1, &n, sizeof n);
    if (!writeAll(fd_, head, sizeof head) || !writeAll(fd_, payload.data(), payload.size()))
        throw ChannelClosed();
}

bool ChildChannel::receive(std::uint8_t& kind, std::string& payload) {
    char head[9];
    if (!readAll(fd_, head, sizeof head)) return false;
    kind = std::uint8_t(head[0]);
    std::uint64_t n;
    std::memcpy(&n, head + 1, sizeof n);
    payload.resize(n);
    return readAll(fd_, payload.data(), n);
}

std::string_view PayloadReader::take(std::size_t n) {
    if (n > rest_.size()) throw std::out_of_range("FST child message too short");
    const std::string_view out = rest_.substr(0, n);
    rest_.remove_prefix(n);
    return out;
}

std::uint64_t PayloadReader::u64() {
    std::uint64_t v;
    std::memcpy(&v, take(sizeof v).data(), sizeof v);
    return v;
}

std::string PayloadReader::text() {
    return std::string(take(std::size_t(u64())));
}

FstChild::FstChild(const std::string& name, std::uint64_t budget, std::uint64_t cpu_seconds,
                   const std::function<void(ChildChannel&)>& body) {
    int fds[2];
    if (::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, fds) != 0)
        throw InputError(
            fmt::format("{}: cannot start the FST reader: {}", name, std::strerror(errno)));
    pid_ = ::fork();
    if (pid_ < 0) {
        const int e = errno;
        ::close(fds[0]);
        ::close(fds[1]);
        throw InputError(
            fmt::format("{}: cannot start the FST reader: {}", name, std::strerror(e)));
    }
    if (pid_ == 0) {
        ::close(fds[0]);
        becomeChild(budget, cpu_seconds);
        ChildChannel out(fds[1]);  // (the parent's buffered output is never flushed here)
        try {
            body(out);
        } catch (...) {  // the parent went away, or memory ran out: nothing left to tell
            ::_exit(3);
        }
        ::_exit(0);
    }
    ::close(fds[1]);
    fd_ = fds[0];
    channel_ = ChildChannel(fd_);
}

FstChild::~FstChild() {
    if (pid_ > 0) {
        ::kill(pid_, SIGKILL);
        while (::waitpid(pid_, nullptr, 0) < 0 && errno == EINTR) {
        }
    }
    if (fd_ >= 0) ::close(fd_);
}

std::string FstChild::howItEnded() {
    if (pid_ <= 0) return "ended";
    int status = 0;
    pid_t r;
    while ((r = ::waitpid(pid_, &status, 0)) < 0 && errno == EINTR) {
    }
    pid_ = -1;
    if (r < 0) return "ended";
    if (WIFSIGNALED(status))
        return fmt::format("killed by signal {} ({})", WTERMSIG(status),
                           strsignal(WTERMSIG(status)));
    return fmt::format("exit status {}", WEXITSTATUS(status));
}

}  // namespace busdecode
