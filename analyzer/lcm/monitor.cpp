#include "monitor.h"

#include <fmt/format.h>
#include <poll.h>
#include <sys/ioctl.h>
#include <termios.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstring>
#include <lcm/lcm-cpp.hpp>

#include "core/options.h"
#include "lcm_channels.h"
#include "lcm_messages.h"
#include "lcm_publisher.h"
#include "lcm_sink.h"
#include "monitor_model.h"

namespace busdecode {

namespace {

constexpr const char* kDefaultUrl = "udpm://239.255.76.67:7667?ttl=0";

std::atomic<bool> g_interrupted{false};
extern "C" void onMonitorSignal(int) {
    g_interrupted = true;
}

// Puts a terminal's input in "one key at a time, no echo" mode so `q` quits without
// Enter, and always gives the terminal back as it was.
class RawInput {
public:
    RawInput() {
        if (!::isatty(STDIN_FILENO) || ::tcgetattr(STDIN_FILENO, &saved_) != 0) return;
        termios raw = saved_;
        raw.c_lflag &= ~tcflag_t(ICANON | ECHO);
        raw.c_cc[VMIN] = 0;
        raw.c_cc[VTIME] = 0;
        active_ = ::tcsetattr(STDIN_FILENO, TCSANOW, &raw) == 0;
    }
    ~RawInput() {
        if (active_) ::tcsetattr(STDIN_FILENO, TCSANOW, &saved_);
    }
    bool active() const { return active_; }
    // True when `q` (or Q, or Esc) was typed.
    bool quitTyped() {
        char c;
        while (active_ && ::read(STDIN_FILENO, &c, 1) == 1)
            if (c == 'q' || c == 'Q' || c == 27) return true;
        return false;
    }

private:
    termios saved_{};
    bool active_ = false;
};

// The alternate screen with a hidden cursor, restored on exit.
class LiveScreen {
public:
    LiveScreen(std::FILE* out, bool on) : out_(out), on_(on) {
        if (on_) std::fputs("\x1b[?1049h\x1b[?25l", out_);
    }
    ~LiveScreen() {
        if (on_) std::fputs("\x1b[?25h\x1b[?1049l", out_), std::fflush(out_);
    }
    void draw(const std::vector<std::string>& lines) {
        std::string s = "\x1b[H";
        for (const auto& l : lines)
            s += l + "\x1b[K\n";
        s += "\nq or Ctrl-C: quit\x1b[K\n\x1b[J";
        std::fputs(s.c_str(), out_);
        std::fflush(out_);
    }

private:
    std::FILE* out_;
    bool on_;
};

std::size_t terminalWidth(std::FILE* out) {
    winsize ws{};
    if (::ioctl(::fileno(out), TIOCGWINSZ, &ws) == 0 && ws.ws_col > 20) return ws.ws_col;
    return 160;
}

void usage(std::FILE* f) {
    std::fputs(
        "usage: decode monitor [--lcm URL] [--once] [--duration SEC]\n"
        "  Shows per bus the latest position, frame rate, CRC error rate, line delay and\n"
        "  register accesses published by `decode --lcm`.\n"
        "  --lcm URL       LCM URL to listen on (default udpm://239.255.76.67:7667?ttl=0)\n"
        "  --once          exit when a decode run ends and print the dashboard once\n"
        "  --duration SEC  exit after SEC seconds\n"
        "  q or Ctrl-C quits.\n",
        f);
}

}  // namespace

Monitor::Monitor(lcm::LCM& lc, MonitorOptions opt)
    : lc_(lc), opt_(std::move(opt)), model_(std::make_unique<MonitorModel>()) {
    MonitorModel* m = model_.get();
    lc.subscribe(lcmChannelFor("ssi", "frame"), &MonitorModel::onSsiFrame, m);
    lc.subscribe(lcmChannelFor("bissc", "frame"), &MonitorModel::onBisscFrame, m);
    lc.subscribe(lcmChannelFor("bissc", "register"), &MonitorModel::onBisscRegister, m);
    lc.subscribe(lcmChannelFor("bissc", "command"), &MonitorModel::onBisscCommand, m);
    lc.subscribe(lcmChannelFor("tmc8100", "encoder_read"), &MonitorModel::onEncoderRead, m);
    lc.subscribe(lcmChannelFor("tmcl", "reply"), &MonitorModel::onTmclReply, m);
    lc.subscribe(kLcmEventsChannel, &MonitorModel::onAnnotation, m);
    lc.subscribe(kLcmStatusChannel, &MonitorModel::onStatus, m);
}

Monitor::~Monitor() = default;

int Monitor::run(std::FILE* out) {
    lcm::LCM& lc = lc_;
    const MonitorOptions& opt = opt_;
    MonitorModel& model = *model_;

    const std::string url = opt.url.empty() ? kDefaultUrl : opt.url;
    const bool live = opt.live && !opt.once;
    RawInput input;
    LiveScreen screen(out, live);
    const std::size_t width = live ? terminalWidth(out) : 160;

    using Clock = std::chrono::steady_clock;
    const auto started = Clock::now();
    auto last_draw = Clock::time_point{};
    const int fd = lc.getFileno();
    for (;;) {
        if (g_interrupted || input.quitTyped()) break;
        if (opt.once && model.runsEnded() > 0) break;
        double elapsed = std::chrono::duration<double>(Clock::now() - started).count();
        if (opt.duration_s > 0 && elapsed >= opt.duration_s) break;
        if (live && Clock::now() - last_draw >= std::chrono::duration<double>(opt.refresh_s)) {
            screen.draw(model.render(url, lcmUtimeNow(), width));
            last_draw = Clock::now();
        }
        pollfd fds[2] = {{fd, POLLIN, 0}, {STDIN_FILENO, POLLIN, 0}};
        int n = ::poll(fds, input.active() ? 2 : 1, 50);
        if (n > 0 && (fds[0].revents & POLLIN)) lc.handle();
    }
    // Whatever is already queued (memq://, or datagrams that arrived meanwhile).
    while (lc.handleTimeout(0) > 0) {
    }
    if (!live) {
        for (const auto& l : model.render(url, lcmUtimeNow(), width))
            fmt::print(out, "{}\n", l);
        std::fflush(out);
    }
    return 0;
}

int runMonitor(int argc, char** argv) {
    MonitorOptions opt;
    opt.live = ::isatty(STDOUT_FILENO);
    std::string url;
    for (int i = 1; i < argc; ++i) {
        std::string a = argv[i];
        auto value = [&](const char* name) -> std::string {
            if (i + 1 >= argc) {
                fmt::print(stderr, "decode monitor: {} needs a value\n", name);
                std::exit(2);
            }
            return argv[++i];
        };
        if (a == "--lcm")
            url = value("--lcm");
        else if (a.rfind("--lcm=", 0) == 0)
            url = a.substr(6);
        else if (a == "--once")
            opt.once = true;
        else if (a == "--duration" || a.rfind("--duration=", 0) == 0) {
            std::string v = a == "--duration" ? value("--duration") : a.substr(11);
            char* end = nullptr;
            opt.duration_s = std::strtod(v.c_str(), &end);
            if (end == v.c_str() || *end || opt.duration_s <= 0) {
                fmt::print(stderr, "decode monitor: --duration '{}': expected seconds > 0\n", v);
                return 2;
            }
        } else if (a == "-h" || a == "--help") {
            usage(stdout);
            return 0;
        } else {
            fmt::print(stderr,
                       "decode monitor: unknown argument '{}' (see decode monitor --help)\n", a);
            return 2;
        }
    }
    opt.url = url;
    std::shared_ptr<lcm::LCM> lc;
    try {
        lc = openLcm(url);
    } catch (const InputError& e) {
        fmt::print(stderr, "decode monitor: {}\n", e.what());
        return 2;
    }
    g_interrupted = false;
    auto old_int = std::signal(SIGINT, onMonitorSignal);
    auto old_term = std::signal(SIGTERM, onMonitorSignal);
    Monitor monitor(*lc, opt);
    // Tell a script (or a test) that the subscription is in place.
    fmt::print(stderr, "decode monitor: listening on {}\n", url.empty() ? kDefaultUrl : url);
    int rc = monitor.run(stdout);
    std::signal(SIGINT, old_int);
    std::signal(SIGTERM, old_term);
    return rc;
}

}  // namespace busdecode
