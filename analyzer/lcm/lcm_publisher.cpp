#include "lcm_publisher.h"

#include <fmt/format.h>

#include <sys/stat.h>
#include <unistd.h>

#include <cctype>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <cstdlib>
#include <deque>
#include <lcm/lcm-cpp.hpp>
#include <mutex>
#include <optional>
#include <thread>
#include <variant>

#include "app/output_guard.h"
#include "busdecode_lcm/decode_status_t.hpp"
#include "core/options.h"
#include "lcm_channels.h"
#include "lcm_messages.h"
#include "lcm_sink.h"
#include "sinks/event_format.h"

namespace busdecode {

namespace {

constexpr const char* kDefaultUrl = "udpm://239.255.76.67:7667?ttl=0";

struct EventItem {
    Event event;
    Timebase tb;
    std::int64_t seq;
};
struct StatusItem {
    std::string state;
    CaptureFacts facts;
    Tick now = 0;
};
using Item = std::variant<EventItem, StatusItem>;

}  // namespace

namespace {

// LCM prints why a URL failed ("Error: Bad multicast port ...") on stderr itself; its
// words are caught here to go into the run's one line of error.
std::shared_ptr<lcm::LCM> openCatchingItsMessage(const std::string& url, std::string& message) {
    std::fflush(stderr);
    std::FILE* caught = std::tmpfile();
    const int saved = caught ? ::dup(STDERR_FILENO) : -1;
    if (saved >= 0) ::dup2(::fileno(caught), STDERR_FILENO);
    auto lc = std::make_shared<lcm::LCM>(url);
    if (saved >= 0) {
        std::fflush(stderr);
        ::dup2(saved, STDERR_FILENO);
        ::close(saved);
        std::rewind(caught);
        char line[512] = {};
        while (std::fgets(line, sizeof line, caught))  // the last line: the failure
            if (line[0] != '\n') message = line;
    }
    if (caught) std::fclose(caught);
    if (message.rfind("Error: ", 0) == 0) message.erase(0, 7);
    while (!message.empty() && std::isspace(static_cast<unsigned char>(message.back())))
        message.pop_back();
    return lc;
}

// Whether `url` writes a new log file (LCM's file provider, mode=w).
bool writesLog(const std::string& url) {
    const auto query = url.find('?');
    if (lcmLogFile(url).empty() || query == std::string::npos) return false;
    const std::string params = "&" + url.substr(query + 1) + "&";
    return params.find("&mode=w&") != std::string::npos;
}

// LCM 1.3.1's file provider drops fwrite's result and the log's fclose's: a log this run
// wrote is read back, and one short of the `published` messages is removed. A device or
// FIFO is written through, as every output is, and not read back.
void checkLogWritten(const std::string& url, std::uint64_t published) {
    if (!writesLog(url)) return;
    const std::string path = lcmLogFile(url);
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0 || !S_ISREG(st.st_mode)) return;
    std::uint64_t found = 0;
    {
        lcm::LogFile log(path, "r");
        while (log.good() && log.readNextEvent())
            ++found;
    }
    if (found >= published) return;
    std::remove(path.c_str());
    throw InputError(
        fmt::format("--lcm: {}: the log holds {} of the {} messages published: "
                    "writing it failed (disk full?); removed",
                    path, found, published));
}

}  // namespace

std::shared_ptr<lcm::LCM> openLcm(const std::string& url) {
    const std::string shown = url.empty() ? kDefaultUrl : url;
    std::string why;
    auto lc = openCatchingItsMessage(url, why);
    // LCM 1.4's tcpq:// without a server stays good() with no socket, and waiting on that
    // aborts the process (FD_SET of -1).
    const bool unconnected = shown.rfind("tcpq://", 0) == 0 && lc->good() && lc->getFileno() < 0;
    if (!lc->good() || unconnected) {
        std::string hint;
        if (shown.rfind("udpm://", 0) == 0 && why.rfind("Bad ", 0) != 0)
            hint =
                " (udpm needs a multicast route; on a machine without a network: "
                "`ip link set lo multicast on; ip route add 224.0.0.0/4 dev lo`)";
        else if (shown.rfind("udpm://", 0) != 0)
            hint =
                " (LCM URLs look like udpm://239.255.76.67:7667?ttl=0, file://log.lcm?mode=w, "
                "memq://)";
        throw InputError(fmt::format("--lcm: cannot open LCM URL '{}'{}{}", shown,
                                     why.empty() ? "" : ": " + why, hint));
    }
    return lc;
}

LcmSinkOptions LcmSinkOptions::fromEnvironment(const std::string& url) {
    LcmSinkOptions o;
    // UDP multicast has no flow control, and LCM 1.3.1 subscribers (lcm-logger, lcm-spy)
    // lose datagrams from back-to-back bursts, which a decoder produces whenever a block of
    // input completes many events at once. A gentle default pace keeps them whole.
    if (url.empty() || url.rfind("udpm://", 0) == 0) o.max_events_per_s = kDefaultUdpmEventsPerS;
    if (const char* q = std::getenv("BUSDECODE_LCM_QUEUE")) {
        char* end = nullptr;
        long long n = std::strtoll(q, &end, 10);
        if (!end || *end || n < 1)
            throw InputError(fmt::format("BUSDECODE_LCM_QUEUE='{}': expected a positive count", q));
        o.queue_capacity = std::size_t(n);
    }
    if (const char* d = std::getenv("BUSDECODE_LCM_DROP")) o.drop_when_full = std::string(d) == "1";
    if (const char* r = std::getenv("BUSDECODE_LCM_RATE")) {
        char* end = nullptr;
        double v = std::strtod(r, &end);
        if (!end || *end || end == r || !(v >= 0))
            throw InputError(fmt::format(
                "BUSDECODE_LCM_RATE='{}': expected events per second (0 = no limit)", r));
        o.max_events_per_s = v;
    }
    return o;
}

struct LcmSink::Impl {
    std::shared_ptr<lcm::LCM> lc;
    std::string url;
    LcmSinkOptions opt;

    std::mutex mu;
    std::condition_variable not_full, not_empty, drained;
    std::deque<Item> queue;
    bool busy = false;  // the publisher holds an item outside the queue
    bool stopping = false;
    LcmSinkCounts counts;
    std::uint64_t messages = 0;  // every message LCM took, statuses included
    LcmSinkCounts reported;      // counts at the previous end(), to report per capture
    std::int64_t next_seq = 0;
    std::string capture_fields;  // the current capture's (captureJsonFields)
    Timebase tb;
    std::thread worker;
    std::chrono::steady_clock::time_point last_live{};  // the last "live" status
    // The capture begun and not yet ended (an interrupted run ends it in the destructor),
    // and the end of its last event so far.
    std::optional<CaptureFacts> open_capture;
    Tick last_end = 0;
    CaptureFacts last_facts;  // the last capture's, for "done"

    void publishStatus(const StatusItem& s) {
        busdecode_lcm::decode_status_t m{};
        m.utime = lcmUtimeNow();
        m.state = s.state;
        m.file = s.facts.file;
        m.format = s.facts.format;
        m.capture_start = s.facts.capture_start;
        m.protos = s.facts.protos;
        m.num_protos = int16_t(m.protos.size());
        m.ns_per_tick = s.facts.timebase.nsPerTick();
        m.capture_ns = s.facts.timebase.toNs(s.now);
        m.live_samples = std::int64_t(s.facts.acquisition.samples);
        m.live_dropped = std::int64_t(s.facts.acquisition.dropped);
        m.live_behind = std::int64_t(s.facts.acquisition.behind);
        std::lock_guard lock(mu);
        m.events = std::int64_t(counts.events);
        m.published = std::int64_t(counts.published);
        m.dropped = std::int64_t(counts.dropped);
        if (lc->publish(kLcmStatusChannel, &m) == 0) ++messages;
    }

    void run() {
        for (;;) {
            Item item;
            {
                std::unique_lock lock(mu);
                not_empty.wait(lock, [&] { return stopping || !queue.empty(); });
                if (queue.empty()) return;  // stopping and drained
                item = std::move(queue.front());
                queue.pop_front();
                busy = true;
            }
            not_full.notify_one();
            if (auto* ev = std::get_if<EventItem>(&item)) {
                if (opt.before_publish) opt.before_publish();
                pace();
                LcmPublishResult r =
                    publishEventToLcm(*lc, ev->event, ev->tb, ev->seq, capture_fields);
                std::lock_guard lock(mu);
                (r.failures ? counts.failed : counts.published)++;
                messages += std::uint64_t(2 - r.failures);  // the typed one and the annotation
            } else {
                publishStatus(std::get<StatusItem>(item));
            }
            {
                std::lock_guard lock(mu);
                busy = false;
            }
            drained.notify_all();
        }
    }

    // Waits for the next publishing slot when a rate is set. A publisher that fell behind
    // (the decoder was slower) starts afresh instead of bursting to catch up.
    std::chrono::steady_clock::time_point next_slot{};
    void pace() {
        if (opt.max_events_per_s <= 0) return;
        using namespace std::chrono;
        auto now = steady_clock::now();
        auto period =
            duration_cast<steady_clock::duration>(duration<double>(1.0 / opt.max_events_per_s));
        if (next_slot < now - 10 * period) next_slot = now;
        if (next_slot > now) std::this_thread::sleep_until(next_slot);
        next_slot += period;
    }

    void push(Item item, bool may_drop) {
        std::unique_lock lock(mu);
        if (queue.size() >= opt.queue_capacity) {
            if (may_drop) {
                counts.dropped++;
                return;
            }
            not_full.wait(lock, [&] { return queue.size() < opt.queue_capacity; });
        }
        queue.push_back(std::move(item));
        lock.unlock();
        not_empty.notify_one();
    }

    void waitDrained() {
        std::unique_lock lock(mu);
        drained.wait(lock, [&] { return queue.empty() && !busy; });
    }
};

LcmSink::LcmSink(std::shared_ptr<lcm::LCM> lcm, std::string url, LcmSinkOptions options)
    : impl_(std::make_unique<Impl>()) {
    impl_->lc = std::move(lcm);
    impl_->url = url.empty() ? kDefaultUrl : std::move(url);
    impl_->opt = std::move(options);
    if (impl_->opt.queue_capacity < 1) impl_->opt.queue_capacity = 1;
    // A first message proves the transport works (an unreachable network fails here,
    // at start, instead of silently losing every event later).
    busdecode_lcm::decode_status_t start{};
    start.utime = lcmUtimeNow();
    start.state = "start";
    if (impl_->lc->publish(kLcmStatusChannel, &start) != 0)
        throw InputError(
            fmt::format("--lcm: cannot publish on '{}' (is the network up?)", impl_->url));
    impl_->messages = 1;
    impl_->worker = std::thread([this] { impl_->run(); });
}

LcmSink::~LcmSink() {
    finish();
}

void LcmSink::finish() {
    if (!impl_->lc) return;
    // Subscribers wait for "done" (subscribe(until_end=True), monitor --once): an
    // interrupted capture is ended first, so they never wait for a run that is over.
    if (impl_->open_capture)
        impl_->push(StatusItem{"end", *impl_->open_capture, impl_->last_end}, false);
    impl_->push(StatusItem{"done", impl_->last_facts, impl_->last_end}, false);
    impl_->waitDrained();
    {
        std::lock_guard lock(impl_->mu);
        impl_->stopping = true;
    }
    impl_->not_empty.notify_all();
    if (impl_->worker.joinable()) impl_->worker.join();
    impl_->lc.reset();  // a file:// log is closed (flushed) here
}

void LcmSink::close() {
    finish();
    checkLogWritten(impl_->url, impl_->messages);
}

void closeLcmSink(OutputSink& sink) {
    static_cast<LcmSink&>(sink).close();
}

void LcmSink::begin(const CaptureFacts& facts) {
    impl_->tb = facts.timebase;
    // Set while the worker is idle (end() drained it); the queue's lock orders it.
    impl_->capture_fields = captureJsonFields(facts, impl_->opt.name_capture);
    impl_->push(StatusItem{"begin", facts, facts.start}, false);
    impl_->open_capture = facts;
    impl_->last_facts = facts;
    impl_->last_end = facts.start;
}

void LcmSink::onEvent(const Event& e, const CaptureFacts& facts) {
    std::int64_t seq;
    {
        std::lock_guard lock(impl_->mu);
        impl_->counts.events++;
        seq = impl_->next_seq++;
    }
    impl_->last_end = e.end;
    impl_->push(EventItem{e, impl_->tb, seq}, impl_->opt.drop_when_full);
    // A live acquisition says how it keeps up while it runs, not only at its end.
    if (facts.acquisition.samples) {
        const auto now = std::chrono::steady_clock::now();
        if (now - impl_->last_live >= std::chrono::seconds(1)) {
            impl_->last_live = now;
            impl_->push(StatusItem{"live", facts, e.end}, false);
        }
    }
}

void LcmSink::end(const CaptureFacts& facts) {
    impl_->waitDrained();  // events first, so "end" carries final counts
    impl_->push(StatusItem{"end", facts, facts.end}, false);
    impl_->open_capture.reset();
    impl_->last_end = facts.end;
    impl_->waitDrained();
    LcmSinkCounts now = counts(), &before = impl_->reported;
    std::uint64_t events = now.events - before.events, dropped = now.dropped - before.dropped,
                  failed = now.failed - before.failed;
    if (dropped && impl_->opt.report)
        fmt::print(impl_->opt.report,
                   "decode: LCM: dropped {} of {} events: the queue ({} events) was full "
                   "(BUSDECODE_LCM_DROP=1; unset it to make decoding wait instead)\n",
                   dropped, events, impl_->opt.queue_capacity);
    if (failed && impl_->opt.report)
        fmt::print(impl_->opt.report,
                   "decode: LCM: {} of {} events could not be published on '{}'\n", failed, events,
                   impl_->url);
    before = now;
}

LcmSinkCounts LcmSink::counts() const {
    std::lock_guard lock(impl_->mu);
    return impl_->counts;
}

std::unique_ptr<OutputSink> makeLcmSink(const std::string& url, bool name_capture) {
    LcmSinkOptions opt = LcmSinkOptions::fromEnvironment(url);
    opt.name_capture = name_capture;
    return std::make_unique<LcmSink>(openLcm(url), url, std::move(opt));
}

}  // namespace busdecode
