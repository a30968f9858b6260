#include "live_reader.h"

#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdlib>
#include <mutex>
#include <thread>

#include <fmt/format.h>

#include "capture_writer.h"
#include "core/options.h"
#include "live_edge_maker.h"
#include "live_save.h"
#include "live_sigrok.h"

namespace busdecode {

namespace {
// A second or so of backlog at a device's packet rate, and 32 MiB of edges: drivers deliver
// in bursts (the demo every 100 ms), which the decoder must be able to take whole.
constexpr std::size_t kQueueBlocks = 4096;
constexpr std::size_t kQueueEdges = 256 * kEdgeBlockSize;

// BUSDECODE_LIVE_QUEUE=N: at most N blocks waiting (as BUSDECODE_LCM_QUEUE for LCM), to
// see how a run that falls behind reports it.
std::size_t queueBlocks() {
    const char* q = std::getenv("BUSDECODE_LIVE_QUEUE");
    if (!q) return kQueueBlocks;
    char* end = nullptr;
    const long long n = std::strtoll(q, &end, 10);
    if (!end || *end || n < 1)
        throw InputError(fmt::format("BUSDECODE_LIVE_QUEUE='{}': expected a positive count", q));
    return std::size_t(n);
}
}  // namespace

class LiveReader : public CaptureReader {
public:
    LiveReader(const LiveSettings& settings, const std::atomic<bool>* stop)
        : settings_(settings), stop_(stop), device_(settings), queue_(queueBlocks(), kQueueEdges) {
        for (std::size_t i = 0; i < device_.channelNames().size(); ++i)
            signals_.push_back({device_.channelNames()[i], device_.channelNames()[i], 1});
        std::uint64_t limit = settings.samples;
        if (settings.seconds > 0) {
            const auto by_time =
                std::uint64_t(std::llround(settings.seconds * double(device_.samplerate())));
            // At least one sample: 0 would mean no limit at all.
            limit = limit ? std::min(limit, std::max<std::uint64_t>(by_time, 1))
                          : std::max<std::uint64_t>(by_time, 1);
        }
        maker_.setLimit(limit);
        if (!settings.save.empty())  // the lines not acquired stay unnamed, as in sigrok's
            saver_ = std::make_unique<LiveSaver>(settings.save, device_.channelNames(),
                                                 device_.samplerate());
    }
    ~LiveReader() override { stopAndJoin(); }

    const std::vector<SignalInfo>& signals() const override { return signals_; }
    Timebase timebase() const override {
        return Timebase::fromSampleRate(std::int64_t(device_.samplerate()));
    }
    std::string formatName() const override {
        return device_.isPlayback() ? "sigrok-playback" : "sigrok-live";
    }
    void select(const std::vector<LineRef>& lines) override {
        checkSelection(lines);
        std::vector<int> bits;
        for (const auto& l : lines)
            bits.push_back(l.signal);
        maker_.select(bits);
    }
    std::vector<std::uint8_t> initialLevels() override;
    Tick startTick() const override { return 0; }
    bool next(EdgeBlock& block) override;
    Tick endTick() const override { return maker_.samples() ? Tick(maker_.samples() - 1) : 0; }
    bool changesOnly() const override { return true; }
    bool readsAhead() const override { return true; }
    AcquisitionCounts acquisition() const override {
        const LiveCounts c = queue_.counts();
        return {c.samples, c.dropped_samples, c.max_lag_samples};
    }
    std::vector<std::string> notes() const override;

    // Why the acquisition ended early ("" = it did not), valid after next() = false.
    std::string failure() const { return queue_.error(); }
    LiveCounts counts() const { return queue_.counts(); }
    // Writes --save's session (nothing when no sample came: notes() says so). Throws
    // InputError.
    void finishSave() {
        if (saver_) saver_->finish();
    }

private:
    void acquire();
    bool onPacket(const std::uint8_t* data, std::size_t n, unsigned unit);
    // Asked again until it ends: a stop that comes before libsigrok runs its loop is lost.
    void stopAndJoin() {
        if (!thread_.joinable()) return;
        std::unique_lock lock(mu_);
        while (!done_) {
            device_.stop();
            started_.wait_for(lock, std::chrono::milliseconds(50), [&] { return done_; });
        }
        lock.unlock();
        thread_.join();
    }

    LiveSettings settings_;
    const std::atomic<bool>* stop_;
    SigrokAcquisition device_;
    std::vector<SignalInfo> signals_;
    LiveEdgeQueue queue_;
    LiveEdgeMaker maker_;
    std::unique_ptr<LiveSaver> saver_;
    std::thread thread_;
    std::mutex mu_;
    std::condition_variable started_;
    bool first_packet_ = false;          // or the acquisition ended without one
    bool done_ = false;                  // the acquisition thread has ended
    std::atomic<bool> stopping_{false};  // next() ended it
};

bool LiveReader::onPacket(const std::uint8_t* data, std::size_t n, unsigned unit) {
    const std::size_t took = queue_.full() ? maker_.dropPacket(data, n, unit, queue_)
                                           : maker_.addPacket(data, n, unit, queue_);
    if (saver_ && took) saver_->add(data, took, unit);
    if (!first_packet_ && maker_.started()) {
        std::lock_guard lock(mu_);
        first_packet_ = true;
        started_.notify_all();
    }
    return !maker_.limitReached();
}

void LiveReader::acquire() {
    std::string error = device_.run(
        [this](const std::uint8_t* d, std::size_t n, unsigned u) { return onPacket(d, n, u); });
    // A device that ends by itself, short of any limit and not asked to, has gone away.
    const bool asked =
        maker_.limitReached() || (stop_ && *stop_) || device_.isPlayback() || stopping_;
    if (error.empty() && !asked) {
        const std::string why = device_.lastLibraryError();
        error = fmt::format("--device {}: the device stopped after {} samples (disconnected?){}",
                            liveCaptureName(settings_), maker_.samples(),
                            why.empty() ? "" : " (libsigrok: " + why + ")");
    }
    queue_.close(error);
    std::lock_guard lock(mu_);
    first_packet_ = done_ = true;
    started_.notify_all();
}

std::vector<std::uint8_t> LiveReader::initialLevels() {
    thread_ = std::thread([this] { acquire(); });
    {
        // A device that sends nothing (a trigger that never fires) still ends on Ctrl-C.
        std::unique_lock lock(mu_);
        while (
            !started_.wait_for(lock, std::chrono::milliseconds(20), [&] { return first_packet_; }))
            if (stop_ && *stop_) break;
    }
    if (!maker_.started()) {
        stopping_ = true;
        stopAndJoin();
    }
    if (maker_.started()) return maker_.initialLevels();
    return std::vector<std::uint8_t>(maker_.initialLevels().size(), 0);
}

bool LiveReader::next(EdgeBlock& block) {
    block.clear();
    if (queue_.pop(block, stop_)) return true;
    stopping_ = true;
    stopAndJoin();
    return false;
}

std::vector<std::string> LiveReader::notes() const {
    const LiveCounts c = queue_.counts();
    const double rate = double(device_.samplerate());
    std::vector<std::string> out;
    out.push_back(fmt::format("{}: {} samples at {}, decoding at most {:.3f} s behind",
                              liveCaptureName(settings_), c.samples,
                              sampleRateText(std::int64_t(device_.samplerate())),
                              double(c.max_lag_samples) / rate));
    if (c.dropped_samples)
        out.push_back(fmt::format(
            "{}: dropped {} samples ({:.3f} s) in {} packets: decoding fell behind the device",
            liveCaptureName(settings_), c.dropped_samples, double(c.dropped_samples) / rate,
            c.dropped_packets));
    // Stopped before the first sample: the run's end is no failure, but nothing is saved.
    if (saver_ && saver_->samples() == 0)
        out.push_back(fmt::format("--save {}: no samples acquired, nothing saved", settings_.save));
    return out;
}

std::unique_ptr<LiveReader> openLive(const LiveSettings& settings, const std::atomic<bool>* stop) {
    return std::make_unique<LiveReader>(settings, stop);
}

CaptureFacts decodeLive(const LiveSettings& settings, const std::vector<DecoderRequest>& requests,
                        const std::vector<OutputSink*>& sinks, const std::atomic<bool>* stop) {
    auto reader = openLive(settings, stop);
    Session session(requests, *reader, liveCaptureName(settings));
    if (stop) session.setStopFlag(stop);
    for (auto* s : sinks)
        session.addSink(s);
    session.run();
    // What was decoded is kept (the sinks have ended); then the save, then the failure.
    reader->finishSave();
    if (!reader->failure().empty()) throw InputError(reader->failure());
    return session.facts();
}

}  // namespace busdecode
