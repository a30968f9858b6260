#include "interruption.h"

#include <csignal>

namespace busdecode {

namespace {

std::atomic<bool> g_stop{false};
std::atomic<int> g_signal{0};
static_assert(std::atomic<int>::is_always_lock_free, "set from a signal handler");

extern "C" void onInterruption(int sig) {
    int none = 0;
    g_signal.compare_exchange_strong(none, sig);  // the first signal names the interruption
    g_stop = true;
}

}  // namespace

void catchInterruptions() {
    struct sigaction action {};
    action.sa_handler = onInterruption;
    sigemptyset(&action.sa_mask);
    action.sa_flags = 0;  // no SA_RESTART: blocking calls return EINTR
    sigaction(SIGINT, &action, nullptr);
    sigaction(SIGTERM, &action, nullptr);
}

const std::atomic<bool>* interruptionFlag() {
    return &g_stop;
}

bool interrupted() {
    return g_stop.load();
}

int interruptedStatus() {
    const int sig = g_signal.load();
    return 128 + (sig ? sig : SIGINT);
}

std::string interruptingSignalName() {
    return g_signal.load() == SIGTERM ? "SIGTERM" : "SIGINT";
}

}  // namespace busdecode
