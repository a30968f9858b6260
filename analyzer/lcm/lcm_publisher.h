#pragma once
// The LCM sink's machinery: a bounded queue between the decoding thread and one
// publisher thread, so a slow network never slows decoding down without bound. Exposed
// for tests, which share one memq:// LCM instance between the sink and a subscriber.
#include <cstdint>
#include <cstdio>
#include <functional>
#include <memory>
#include <string>

#include "core/session.h"

namespace lcm {
class LCM;
}

namespace busdecode {

struct LcmSinkOptions {
    // Events waiting to be published, at most. BUSDECODE_LCM_QUEUE overrides.
    std::size_t queue_capacity = 4096;
    // When the queue is full: false = the decoder waits (nothing is lost), true = the
    // event is dropped and counted. BUSDECODE_LCM_DROP=1 sets it.
    bool drop_when_full = false;
    // Events published per second at most (0 = as fast as they come). UDP subscribers
    // (lcm-logger, lcm-spy) lose datagrams when a file is decoded far faster than they
    // read; pacing the publisher thread keeps them whole. BUSDECODE_LCM_RATE sets it;
    // udpm:// URLs default to kDefaultUdpmEventsPerS.
    static constexpr double kDefaultUdpmEventsPerS = 20000;
    double max_events_per_s = 0;
    // Each annotation's json names its capture, as jsonl does with several captures in one
    // call (docs/contract.md, "JSON lines").
    bool name_capture = false;
    // Where the end-of-capture drop/failure counts go.
    std::FILE* report = stderr;
    // Test hook: called by the publisher thread before each event it publishes.
    std::function<void()> before_publish;

    // Defaults for `url` with BUSDECODE_LCM_QUEUE / BUSDECODE_LCM_DROP / BUSDECODE_LCM_RATE
    // applied (throws InputError on a bad value).
    static LcmSinkOptions fromEnvironment(const std::string& url);
};

// Counts of one sink, for the end report and tests.
struct LcmSinkCounts {
    std::uint64_t events = 0;     // handed to the sink
    std::uint64_t published = 0;  // published (typed + annotation)
    std::uint64_t dropped = 0;    // dropped because the queue was full (drop mode only)
    std::uint64_t failed = 0;     // events whose publish LCM refused
};

class LcmSink : public OutputSink {
public:
    // Publishes a "start" status message at once: throws InputError if LCM refuses it.
    LcmSink(std::shared_ptr<lcm::LCM> lcm, std::string url, LcmSinkOptions options);
    ~LcmSink() override;
    void begin(const CaptureFacts& facts) override;
    void onEvent(const Event& e, const CaptureFacts& facts) override;
    // Waits until everything queued is published, then reports drops and failures.
    void end(const CaptureFacts& facts) override;
    LcmSinkCounts counts() const;
    // Publishes the run's end ("done") and closes LCM. A log this run wrote (file://
    // mode=w) is read back: LCM's file provider never says a write failed, so a log short
    // of the messages published (a full disk) is removed and InputError thrown. The
    // destructor closes too, without that check.
    void close();

    struct Impl;

private:
    void finish();
    std::unique_ptr<Impl> impl_;
};

// Opens `url` ("" = LCM's default) and checks it; InputError with a hint when it fails.
std::shared_ptr<lcm::LCM> openLcm(const std::string& url);

}  // namespace busdecode
