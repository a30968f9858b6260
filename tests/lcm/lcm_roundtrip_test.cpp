// The real round trip: the real `lcm-logger` records `decode --lcm` on LCM's default
// multicast URL, and the log, read back with LCM's EventLog API (lcm::LogFile), holds
// one typed message and one annotation per decoded event, on the contract's channels,
// with fields equal to the `--format jsonl` output of the same run.
//
// Isolation: the logger and the decoder run in a child process that has its own network
// namespace (unshare(CLONE_NEWNET), as root) with multicast enabled on its loopback, so
// the test needs no network and cannot see or disturb other LCM traffic on the machine.
// Without the privilege for that, the child uses the host's network if a multicast route
// exists, and the test is skipped (saying why) if neither works.
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <net/if.h>
#include <net/route.h>
#include <netinet/in.h>
#include <sched.h>
#include <signal.h>
#include <sys/ioctl.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <lcm/lcm-cpp.hpp>
#include <memory>
#include <set>
#include <sstream>
#include <thread>

#include "busdecode_lcm/decode_status_t.hpp"
#include "busdecode_lcm/event_annotation_t.hpp"
#include "decode_process.h"
#include "lcm/lcm_channels.h"
#include "lcm_message_view.h"
#include "support/paths.h"
#include "uart_vcd.h"
#include "value_compare.h"

namespace busdecode {
namespace {

using namespace std::chrono_literals;

constexpr const char* kDefaultUrl = "udpm://239.255.76.67:7667?ttl=0";
// The URL the child uses: LCM's default in a private namespace; on the host's network a
// port of this process's own, so two tests running at once do not see each other.
std::string g_url = kDefaultUrl;
// UDP has no flow control. The logger's LCM (1.3.1) moves datagrams from its socket into
// a 200 KB ring and dispatches from there; when the logger is starved of CPU (a busy
// 2-core machine) the ring overflows. So: a big socket buffer, and the decoder paced to
// 500 events (1000 datagrams, ~0.5 MB) per second, which rides out stalls of ~0.25 s.
constexpr const char* kLoggerUrlOptions = "&recv_buf_size=4194304";
constexpr const char* kRate = "500";

struct Case {
    std::string name;
    std::vector<std::string> args;    // capture and decoder arguments
    std::vector<std::string> protos;  // protocols it must produce events of
};

// Real captures, so every protocol is decoded from traffic nobody here made up; nulls
// (short frames), errors (checksum) and two decoders in one pass included. Then the
// repository's generated examples for what no public capture has: BiSS-C register
// accesses, TMC8100 encoder reads cross-checked with SSI, real TMCL, Gray SSI.
std::vector<Case> cases() {
    const std::string s = test::realCaptures(), c = test::sourceDir() + "/captures";
    std::vector<Case> out{
        {"bissc",
         {s + "/biss-renishaw/sr/renishaw_biss_1MHz.sr", "--proto", "bissc", "--opt", "bits=32"},
         {"bissc"}},
        {"ssi",
         {s + "/sigrok-dumps/caliper/caliper0.55mm.sr", "--proto", "ssi", "--opt", "bits=24"},
         {"ssi"}},
        {"spi",
         {s + "/sigrok-dumps/spi/adf4351/set-4000mhz.sr", "--proto", "spi", "--opt", "cpol=0",
          "--opt", "cpha=0"},
         {"spi"}},
        {"tmc8100",
         {s + "/sigrok-dumps/spi/adf4351/set-4000mhz.sr", "--proto", "tmc8100"},
         {"tmc8100"}},
        {"uart+tmcl",
         {s + "/sigrok-dumps/uart/modbus_rtu/wizmodbus/wizmodbus.sr", "--proto", "uart", "--proto",
          "tmcl"},
         {"uart", "tmcl"}},
    };
    // Examples that other work may still be adding: used when present.
    std::vector<Case> examples{
        {"bissc registers", {c + "/bissc_1mhz_26bit.vcd", "--proto", "bissc"}, {"bissc"}},
        {"tmc8100+ssi",
         {c + "/tmc8100_ssi_dialogue.vcd", "--proto", "tmc8100", "--proto", "ssi"},
         {"tmc8100", "ssi"}},
        {"tmcl lines",
         {c + "/tmcl_lines_115200.vcd", "--proto", "tmcl", "--opt", "baud=115200"},
         {"tmcl"}},
        {"ssi gray", {c + "/ssi_tmc8100_gray25.vcd", "--proto", "ssi", "--opt", "gray=1"}, {"ssi"}},
    };
    for (auto& e : examples) {
        if (std::ifstream(e.args[0]).good())
            out.push_back(std::move(e));
        else
            std::cout << "note: " << e.args[0] << " is not in the repository yet\n";
    }
    return out;
}

bool fileContains(const std::string& path, const std::string& needle) {
    std::ifstream f(path, std::ios::binary);
    std::stringstream ss;
    ss << f.rdbuf();
    return ss.str().find(needle) != std::string::npos;
}

// Publishes `channel` until the logger has written it to `log` (the logger flushes every
// 20 ms): proves the logger is subscribed, or that everything before it was logged.
bool publishUntilLogged(lcm::LCM& lc, const std::string& channel, const std::string& log) {
    for (int i = 0; i < 400; ++i) {
        lc.publish(channel, "x", 1);
        std::this_thread::sleep_for(50ms);
        if (fileContains(log, channel)) return true;
    }
    return false;
}

// In a fresh network namespace: loopback up with multicast, and the multicast range
// routed to it (what `ip link set lo up multicast on; ip route add 224.0.0.0/4 dev lo`
// does, without needing iproute2).
bool enableLoopbackMulticast() {
    int s = ::socket(AF_INET, SOCK_DGRAM, 0);
    if (s < 0) return false;
    ifreq ifr{};
    std::strcpy(ifr.ifr_name, "lo");
    bool ok = ::ioctl(s, SIOCGIFFLAGS, &ifr) == 0;
    ifr.ifr_flags |= IFF_UP | IFF_RUNNING | IFF_MULTICAST;
    ok = ok && ::ioctl(s, SIOCSIFFLAGS, &ifr) == 0;
    rtentry rt{};
    auto* dst = reinterpret_cast<sockaddr_in*>(&rt.rt_dst);
    auto* mask = reinterpret_cast<sockaddr_in*>(&rt.rt_genmask);
    dst->sin_family = mask->sin_family = AF_INET;
    dst->sin_addr.s_addr = htonl(0xE0000000);   // 224.0.0.0
    mask->sin_addr.s_addr = htonl(0xF0000000);  // /4
    rt.rt_flags = RTF_UP;
    char dev[] = "lo";
    rt.rt_dev = dev;
    ok = ok && ::ioctl(s, SIOCADDRT, &rt) == 0;
    ::close(s);
    return ok;
}

void writeText(const std::string& path, const std::string& text) {
    std::ofstream(path) << text;
}

// In a forked child: the network (a private namespace, or the host's), and lcm-logger
// recording `dir`/decode.lcmlog, subscribed for sure. Communicates through files in `dir`
// only. Exit codes: 20+ setup failures (explained in `dir`/setup.txt).
struct Logging {
    std::string log;
    pid_t logger = -1;
    std::unique_ptr<lcm::LCM> probe;
};

int startLogging(const std::string& dir, Logging& g) {
    std::string network = "host";
    if (::unshare(CLONE_NEWNET) == 0) {
        network = "namespace";
        if (!enableLoopbackMulticast()) {
            writeText(dir + "/setup.txt", "could not enable multicast on the namespace's loopback");
            return 20;
        }
    }
    if (network == "host")
        g_url = "udpm://239.255.76.67:" + std::to_string(7700 + ::getpid() % 200) + "?ttl=0";
    writeText(dir + "/network.txt", network + " " + g_url);
    g.probe = std::make_unique<lcm::LCM>(g_url);
    if (!g.probe->good()) {
        writeText(dir + "/setup.txt", "no multicast route (and no network namespace: not root?)");
        return 21;
    }
    g.log = dir + "/decode.lcmlog";
    g.logger = ::fork();
    if (g.logger == 0) {
        std::string url_arg = "--lcm-url=" + g_url + kLoggerUrlOptions;
        ::execlp("lcm-logger", "lcm-logger", "-f", "-q", "--flush-interval=20", url_arg.c_str(),
                 g.log.c_str(), (char*)nullptr);
        ::_exit(127);
    }
    if (!publishUntilLogged(*g.probe, "BUSDECODE_PROBE", g.log)) {
        ::kill(g.logger, SIGKILL);
        writeText(dir + "/setup.txt", "lcm-logger did not start (is liblcm-bin installed?)");
        return 22;
    }
    return 0;
}

// Waits until everything published so far is in the log, then stops the logger.
int stopLogging(const std::string& dir, Logging& g) {
    bool flushed = publishUntilLogged(*g.probe, "BUSDECODE_PROBE_END", g.log);
    ::kill(g.logger, SIGINT);
    int st = 0;
    ::waitpid(g.logger, &st, 0);
    if (!flushed) {
        writeText(dir + "/setup.txt", "lcm-logger stopped logging");
        return 23;
    }
    return 0;
}

bool waitForExit(pid_t pid, std::chrono::seconds limit) {
    auto deadline = std::chrono::steady_clock::now() + limit;
    while (std::chrono::steady_clock::now() < deadline) {
        if (::waitpid(pid, nullptr, WNOHANG) == pid) return true;
        std::this_thread::sleep_for(20ms);
    }
    ::kill(pid, SIGKILL);
    ::waitpid(pid, nullptr, 0);
    return false;
}

// The round trip's child: logger, monitor, one decode per case.
int runChild(const std::string& dir) {
    Logging g;
    if (int rc = startLogging(dir, g)) return rc;
    // The dashboard watches the first run and must exit by itself when it ends.
    const std::string bin = test::binDir() + "/decode";
    pid_t monitor = ::fork();
    if (monitor == 0) {
        std::freopen((dir + "/monitor.txt").c_str(), "w", stdout);
        std::freopen((dir + "/monitor_err.txt").c_str(), "w", stderr);
        ::execl(bin.c_str(), bin.c_str(), "monitor", "--once", "--duration", "60", "--lcm",
                g_url.c_str(), (char*)nullptr);
        ::_exit(127);
    }
    for (int i = 0; i < 400 && !fileContains(dir + "/monitor_err.txt", "listening"); ++i)
        std::this_thread::sleep_for(25ms);

    // Paced so that the logger (and the monitor) read every datagram: UDP has no flow
    // control, and a file decodes much faster than they read.
    ::setenv("BUSDECODE_LCM_RATE", kRate, 1);
    auto all = cases();
    for (std::size_t i = 0; i < all.size(); ++i) {
        std::string cmd = test::shellQuote(bin);
        for (const auto& a : all[i].args)
            cmd += " " + test::shellQuote(a);
        cmd += " --format jsonl --lcm " + test::shellQuote(g_url);
        std::string base = dir + "/case" + std::to_string(i);
        int st = std::system((cmd + " > " + base + ".jsonl 2> " + base + ".err").c_str());
        writeText(base + ".status", std::to_string(WIFEXITED(st) ? WEXITSTATUS(st) : -1));
    }
    writeText(dir + "/monitor_exited.txt", waitForExit(monitor, 10s) ? "yes" : "no");
    return stopLogging(dir, g);
}

// The live child: a capture written to `decode - --follow --lcm` in two parts; between
// them, the logger must already hold the first part's events.
constexpr const char* kLiveText = "Live over LCM while the capture is still being written.";
constexpr std::size_t kLiveSplit = 24;

int countLogged(const std::string& log, const std::string& channel) {
    lcm::LogFile f(log, "r");
    int n = 0;
    if (!f.good()) return 0;
    while (const lcm::LogEvent* ev = f.readNextEvent())
        if (ev->channel == channel) n++;
    return n;
}

int runLiveChild(const std::string& dir) {
    Logging g;
    if (int rc = startLogging(dir, g)) return rc;
    ::setenv("BUSDECODE_LCM_RATE", kRate, 1);
    test::UartVcd vcd = test::uartVcd(kLiveText, kLiveSplit);
    test::DecodeProcess d = test::spawnDecode({"-", "--follow", "--proto", "uart", "--opt",
                                               "baud=10000", "--format", "jsonl", "--lcm", g_url});
    if (d.pid <= 0 || !test::writeAll(d.in, vcd.head)) return 30;
    int early = 0;
    for (int i = 0; i < 1000 && early < int(kLiveSplit); ++i) {
        // lcm-logger flushes its file when a message arrives: keep one coming.
        g.probe->publish("BUSDECODE_PROBE", "x", 1);
        std::this_thread::sleep_for(20ms);
        early = countLogged(g.log, "DECODE_UART_BYTE");
    }
    writeText(dir + "/early.txt", std::to_string(early));
    if (!test::writeAll(d.in, vcd.tail)) return 31;
    ::close(d.in);
    std::string out;
    char buf[4096];
    for (ssize_t n; (n = ::read(d.out, buf, sizeof buf)) > 0;)
        out.append(buf, std::size_t(n));
    writeText(dir + "/live.jsonl", out);
    int st = 0;
    ::waitpid(d.pid, &st, 0);
    writeText(dir + "/live.status", std::to_string(WIFEXITED(st) ? WEXITSTATUS(st) : -1));
    return stopLogging(dir, g);
}

// Forks `child` in `dir` and returns its exit code (or skips/fails the test).
int forkChild(const std::string& dir, int (*child)(const std::string&)) {
    std::fflush(nullptr);
    pid_t pid = ::fork();
    if (pid == 0) ::_exit(child(dir));
    int st = 0;
    if (::waitpid(pid, &st, 0) != pid || !WIFEXITED(st)) return -1;
    return WEXITSTATUS(st);
}

Value fromJson(const QJsonValue& v) {
    if (v.isNull() || v.isUndefined()) return Null{};
    if (v.isBool()) return v.toBool();
    if (v.isString()) return v.toString().toStdString();
    if (v.isArray()) {
        std::vector<std::int64_t> out;
        for (const auto& x : v.toArray())
            out.push_back(x.toInteger());
        return out;
    }
    double d = v.toDouble();
    if (d == std::floor(d) && std::fabs(d) < 9e15) return std::int64_t(v.toInteger());
    return d;
}

std::vector<QJsonObject> readJsonl(const std::string& path) {
    std::vector<QJsonObject> out;
    std::ifstream f(path);
    std::string line;
    while (std::getline(f, line)) {
        QJsonParseError err;
        auto doc = QJsonDocument::fromJson(QByteArray::fromStdString(line), &err);
        EXPECT_TRUE(doc.isObject()) << path << ": " << line;
        out.push_back(doc.object());
    }
    return out;
}

struct LoggedRun {
    std::vector<std::string> lines_json;  // annotations' json, in log order
    std::vector<busdecode_lcm::event_annotation_t> notes;
    std::vector<std::pair<std::string, std::vector<std::uint8_t>>> typed;
    std::vector<busdecode_lcm::decode_status_t> status;
};

std::vector<LoggedRun> readLog(const std::string& path) {
    std::vector<LoggedRun> runs;
    lcm::LogFile log(path, "r");
    EXPECT_TRUE(log.good()) << path;
    while (const lcm::LogEvent* ev = log.readNextEvent()) {
        if (ev->channel.rfind("BUSDECODE_PROBE", 0) == 0 || ev->channel == "LCM_SELF_TEST")
            continue;
        if (ev->channel == kLcmStatusChannel) {
            busdecode_lcm::decode_status_t s;
            EXPECT_GE(s.decode(ev->data, 0, ev->datalen), 0);
            if (s.state == "start") runs.emplace_back();
            if (!runs.empty()) runs.back().status.push_back(s);
            continue;
        }
        EXPECT_FALSE(runs.empty()) << "message before any run: " << ev->channel;
        if (runs.empty()) continue;
        if (ev->channel == kLcmEventsChannel) {
            busdecode_lcm::event_annotation_t a;
            EXPECT_GE(a.decode(ev->data, 0, ev->datalen), 0);
            runs.back().notes.push_back(a);
        } else {
            auto p = static_cast<const std::uint8_t*>(ev->data);
            runs.back().typed.emplace_back(ev->channel,
                                           std::vector<std::uint8_t>(p, p + ev->datalen));
        }
    }
    return runs;
}

// Runs the child (every case decoded with --lcm, lcm-logger recording) and reads its log.
// UDP may still lose a datagram when the machine is starved of CPU (the logger does not
// run for a quarter of a second): such an attempt is repeated, up to 3 times. A wrong
// channel, field or count from our side fails every attempt the same way. Empty with
// `skip` set when the network cannot be set up; `dir` is the last attempt's folder.
std::vector<LoggedRun> logEveryCase(const std::vector<Case>& all, std::string& dir,
                                    std::string& skip) {
    std::vector<LoggedRun> runs;
    for (int attempt = 1; attempt <= 3; ++attempt) {
        dir = test::tempDir() + "/roundtrip" + std::to_string(attempt);
        EXPECT_EQ(std::system(("mkdir -p " + dir).c_str()), 0);
        const int rc = forkChild(dir, runChild);
        if (rc == 21) {
            skip = test::readFile(dir + "/setup.txt");
            return {};
        }
        EXPECT_EQ(rc, 0) << test::readFile(dir + "/setup.txt");
        std::cout << "network: " << test::readFile(dir + "/network.txt") << "\n";
        runs = readLog(dir + "/decode.lcmlog");
        std::string lost;
        for (std::size_t i = 0; i < all.size() && i < runs.size(); ++i) {
            std::size_t n = readJsonl(dir + "/case" + std::to_string(i) + ".jsonl").size();
            if (runs[i].notes.size() < n || runs[i].typed.size() < n || runs[i].status.size() < 3)
                lost += " " + all[i].name;
        }
        if (lost.empty()) break;
        std::cout << "attempt " << attempt << ": datagrams lost in" << lost << "\n";
    }
    return runs;
}

// Line k of the jsonl against the k-th annotation and typed message of its run.
void expectLoggedAsLine(const LoggedRun& run, std::size_t k, const QJsonObject& o,
                        const std::string& raw_line) {
    const auto& note = run.notes[k];
    const std::string proto = o["proto"].toString().toStdString(),
                      type = o["type"].toString().toStdString();
    const std::string channel = "DECODE_" + QString::fromStdString(proto).toUpper().toStdString() +
                                "_" + QString::fromStdString(type).toUpper().toStdString();
    EXPECT_EQ(note.seq, std::int64_t(k));
    EXPECT_EQ(note.json, raw_line) << "annotation json = jsonl line";
    EXPECT_EQ(note.channel, channel);

    const auto& [ch, bytes] = run.typed[k];
    EXPECT_EQ(ch, channel) << "line " << k;
    auto v = test::viewEventMessage(ch, bytes.data(), int(bytes.size()));
    ASSERT_TRUE(v);
    EXPECT_EQ(v->seq, std::int64_t(k));
    EXPECT_EQ(v->start_ns, o["start_ns"].toInteger()) << "line " << k;
    EXPECT_EQ(v->end_ns, o["end_ns"].toInteger()) << "line " << k;
    std::vector<std::string> errors;
    for (const auto& e : o["errors"].toArray())
        errors.push_back(e.toString().toStdString());
    EXPECT_EQ(v->errors, errors) << "line " << k;
    for (const auto& [key, value] : v->fields) {
        QJsonValue jv = o.value(QString::fromStdString(key));
        Value want = fromJson(jv);
        EXPECT_EQ(test::compareValues(value, jv.isUndefined() ? nullptr : &want), "")
            << ch << " line " << k << " field " << key << ": " << raw_line;
    }
}

// One case's run against its jsonl (`base`.jsonl): every line logged, in order, and the
// run's status. The number of lines, or 0 when the case failed.
std::size_t expectRunAsJsonl(const LoggedRun& run, const Case& c, const std::string& base) {
    EXPECT_EQ(test::readFile(base + ".status"), "0") << test::readFile(base + ".err");
    auto lines = readJsonl(base + ".jsonl");
    EXPECT_FALSE(lines.empty());
    std::set<std::string> protos;
    for (const auto& o : lines)
        protos.insert(o["proto"].toString().toStdString());
    for (const auto& p : c.protos)
        EXPECT_TRUE(protos.count(p)) << "no " << p << " events";

    // One annotation and one typed message per jsonl line, in order.
    EXPECT_EQ(run.notes.size(), lines.size());
    EXPECT_EQ(run.typed.size(), lines.size());
    if (run.notes.size() != lines.size() || run.typed.size() != lines.size()) return 0;
    std::ifstream jf(base + ".jsonl");
    std::string raw_line;
    for (std::size_t k = 0; k < lines.size(); ++k) {
        std::getline(jf, raw_line);
        expectLoggedAsLine(run, k, lines[k], raw_line);
    }
    EXPECT_FALSE(run.status.empty());
    if (run.status.empty()) return 0;
    EXPECT_EQ(run.status.back().state, "done");
    if (run.status.size() < 2) {
        ADD_FAILURE() << "no end before done";
        return 0;
    }
    const auto& end = run.status[run.status.size() - 2];
    EXPECT_EQ(end.state, "end");
    EXPECT_EQ(end.events, std::int64_t(lines.size()));
    EXPECT_EQ(end.dropped, 0);
    return lines.size();
}

// The dashboard saw the first run (BiSS-C frames) and exited by itself.
void expectMonitorSawFirstRun(const std::string& dir) {
    EXPECT_EQ(test::readFile(dir + "/monitor_exited.txt"), "yes");
    std::string monitor = test::readFile(dir + "/monitor.txt");
    EXPECT_NE(monitor.find("[ended]"), std::string::npos) << monitor;
    // The first capture's path, cut at the dashboard's width however deep the checkout lies.
    const std::string first = test::realCaptures() + "/biss-renishaw/sr/renishaw_biss_1MHz.sr";
    const auto at = monitor.find("capture /");
    ASSERT_NE(at, std::string::npos) << monitor;
    const std::string shown = monitor.substr(at + 8, monitor.find_first_of(" \n", at + 8) - at - 8);
    EXPECT_GE(shown.size(), 20u) << monitor;
    EXPECT_EQ(first.compare(0, shown.size(), shown), 0) << shown << "\n" << monitor;
    EXPECT_NE(monitor.find("bissc"), std::string::npos) << monitor;
}

TEST(LcmRoundTrip, LoggerRecordsEveryEventOfEveryProtocolAsTheJsonlSaysIt) {
    if (std::system("command -v lcm-logger > /dev/null") != 0)
        GTEST_SKIP() << "lcm-logger not installed";
    const auto all = cases();
    std::string dir, skip;
    const std::vector<LoggedRun> runs = logEveryCase(all, dir, skip);
    if (!skip.empty()) GTEST_SKIP() << skip;
    ASSERT_FALSE(HasFailure());
    ASSERT_EQ(runs.size(), all.size()) << "one decode run per case";
    std::size_t total = 0;
    for (std::size_t i = 0; i < all.size(); ++i) {
        SCOPED_TRACE(all[i].name);
        total += expectRunAsJsonl(runs[i], all[i], dir + "/case" + std::to_string(i));
    }
    std::cout << "logged " << total << " events of " << all.size() << " captures\n";
    // Every typed message kind that real or example traffic produces went through
    // (bissc/command has no capture yet: the memq tests cover it).
    std::set<std::string> channels;
    for (const auto& r : runs)
        for (const auto& t : r.typed)
            channels.insert(t.first);
    std::vector<std::string> expected{
        "DECODE_SSI_FRAME",       "DECODE_BISSC_FRAME",   "DECODE_SPI_TRANSFER",
        "DECODE_TMC8100_COMMAND", "DECODE_TMC8100_REPLY", "DECODE_TMC8100_ENCODER_READ",
        "DECODE_UART_BYTE",       "DECODE_TMCL_COMMAND",  "DECODE_TMCL_REPLY"};
    for (const auto& c : all)
        if (c.name == "bissc registers") expected.push_back("DECODE_BISSC_REGISTER");
    for (const auto& ch : expected)
        EXPECT_TRUE(channels.count(ch)) << ch;
    expectMonitorSawFirstRun(dir);
}

TEST(LcmRoundTrip, AFollowedPipeIsPublishedWhileTheWriterIsStillWriting) {
    if (std::system("command -v lcm-logger > /dev/null") != 0)
        GTEST_SKIP() << "lcm-logger not installed";
    const std::string dir = test::tempDir() + "/live";
    ASSERT_EQ(std::system(("mkdir -p " + dir).c_str()), 0);
    int rc = forkChild(dir, runLiveChild);
    if (rc == 21) GTEST_SKIP() << test::readFile(dir + "/setup.txt");
    ASSERT_EQ(rc, 0) << test::readFile(dir + "/setup.txt");
    ASSERT_EQ(test::readFile(dir + "/live.status"), "0");
    // The first part's bytes were on LCM (and in the logger's file) before the writer sent
    // the rest.
    EXPECT_EQ(test::readFile(dir + "/early.txt"), std::to_string(kLiveSplit));

    const std::string text = kLiveText;
    auto runs = readLog(dir + "/decode.lcmlog");
    ASSERT_EQ(runs.size(), 1u);
    auto lines = readJsonl(dir + "/live.jsonl");
    ASSERT_EQ(lines.size(), text.size());
    ASSERT_EQ(runs[0].typed.size(), text.size());
    ASSERT_EQ(runs[0].notes.size(), text.size());
    for (std::size_t i = 0; i < text.size(); ++i) {
        const auto& [ch, bytes] = runs[0].typed[i];
        EXPECT_EQ(ch, "DECODE_UART_BYTE");
        auto v = test::viewEventMessage(ch, bytes.data(), int(bytes.size()));
        ASSERT_TRUE(v);
        EXPECT_EQ(asInt(v->fields.at("value")), static_cast<unsigned char>(text[i])) << i;
        EXPECT_EQ(v->start_ns, lines[i]["start_ns"].toInteger());
    }
}

}  // namespace
}  // namespace busdecode
