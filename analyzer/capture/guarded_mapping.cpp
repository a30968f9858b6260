#include "guarded_mapping.h"

#include <array>
#include <csignal>
#include <mutex>

#include <sys/mman.h>
#include <unistd.h>

namespace busdecode {

namespace {

// The windows the handler mends: a fixed table, since a signal handler can neither lock
// nor allocate. An entry is published by writing its end, flag, then begin (release), and
// withdrawn by clearing begin first; the handler reads begin, end, then begin again, so
// that it never takes one window's begin with another's end.
struct Window {
    std::atomic<std::uintptr_t> begin{0};
    std::atomic<std::uintptr_t> end{0};
    std::atomic<std::atomic<bool>*> shrunk{nullptr};
    std::atomic<bool> taken{false};
};
// Two readers (verify --jobs 2) with kPiecesAhead windows each, and room to spare.
constexpr std::size_t kWindows = 64;
std::array<Window, kWindows> windows;

struct sigaction previous_action;
std::once_flag install_once;
bool installed = false;

std::uintptr_t pageSize() {
    static const std::uintptr_t size = std::uintptr_t(::sysconf(_SC_PAGESIZE));
    return size;
}

void onSigbus(int sig, siginfo_t* info, void* context) {
    const auto at = reinterpret_cast<std::uintptr_t>(info->si_addr);
    for (Window& w : windows) {
        const std::uintptr_t begin = w.begin.load(std::memory_order_acquire);
        if (begin == 0 || at < begin) continue;
        const std::uintptr_t end = w.end.load(std::memory_order_acquire);
        std::atomic<bool>* shrunk = w.shrunk.load(std::memory_order_acquire);
        if (w.begin.load(std::memory_order_acquire) != begin || at >= end) continue;
        // The flag first: a thread that sees the zeros below then sees it set too.
        if (shrunk) shrunk->store(true, std::memory_order_seq_cst);
        const std::uintptr_t page = at & ~(pageSize() - 1);
        void* zeros = ::mmap(reinterpret_cast<void*>(page), end - page, PROT_READ,
                             MAP_PRIVATE | MAP_ANONYMOUS | MAP_FIXED, -1, 0);
        if (zeros != MAP_FAILED) return;  // the read is retried, over zeros
        break;
    }
    // Not a window of ours: what would have happened without this handler.
    if ((previous_action.sa_flags & SA_SIGINFO) && previous_action.sa_sigaction) {
        previous_action.sa_sigaction(sig, info, context);
    } else if (!(previous_action.sa_flags & SA_SIGINFO) && previous_action.sa_handler != SIG_DFL &&
               previous_action.sa_handler != SIG_IGN) {
        previous_action.sa_handler(sig);
    } else {
        // The fault recurs when the access is retried, and kills the process as SIGBUS.
        std::signal(sig, SIG_DFL);
    }
}

bool installHandler() {
    std::call_once(install_once, [] {
        struct sigaction action {};
        action.sa_sigaction = onSigbus;
        action.sa_flags = SA_SIGINFO;
        sigemptyset(&action.sa_mask);
        installed = ::sigaction(SIGBUS, &action, &previous_action) == 0;
    });
    return installed;
}

int claimWindow() {
    for (std::size_t i = 0; i < kWindows; ++i) {
        bool free = false;
        if (windows[i].taken.compare_exchange_strong(free, true, std::memory_order_acq_rel))
            return int(i);
    }
    return -1;
}

}  // namespace

bool GuardedMapping::map(int fd, std::uint64_t from, std::uint64_t to, std::atomic<bool>* shrunk) {
    unmap();
    if (to <= from || !installHandler()) return false;
    const int slot = claimWindow();
    if (slot < 0) return false;
    const std::uint64_t start = from & ~std::uint64_t(pageSize() - 1);
    const std::size_t length = std::size_t(to - start);
    void* base = ::mmap(nullptr, length, PROT_READ, MAP_PRIVATE, fd, off_t(start));
    if (base == MAP_FAILED) {
        windows[std::size_t(slot)].taken.store(false, std::memory_order_release);
        return false;
    }
    Window& w = windows[std::size_t(slot)];
    const auto begin = reinterpret_cast<std::uintptr_t>(base);
    w.end.store(begin + length, std::memory_order_release);
    w.shrunk.store(shrunk, std::memory_order_release);
    w.begin.store(begin, std::memory_order_release);
    base_ = base;
    length_ = length;
    data_ = static_cast<const char*>(base) + (from - start);
    slot_ = slot;
    return true;
}

void GuardedMapping::unmap() {
    if (!base_) return;
    Window& w = windows[std::size_t(slot_)];
    w.begin.store(0, std::memory_order_release);  // withdrawn before the pages go
    ::munmap(base_, length_);
    w.shrunk.store(nullptr, std::memory_order_release);
    w.end.store(0, std::memory_order_release);
    w.taken.store(false, std::memory_order_release);
    base_ = nullptr;
    data_ = nullptr;
    length_ = 0;
    slot_ = -1;
}

}  // namespace busdecode
