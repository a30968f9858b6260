#pragma once
// --realtime: a reader that hands out blocks no faster than the capture's own time runs.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <memory>
#include <thread>

#include "capture/capture_reader.h"

namespace busdecode {

class PacedReader : public CaptureReader {
public:
    PacedReader(std::unique_ptr<CaptureReader> inner, const std::atomic<bool>* stop)
        : in_(std::move(inner)), stop_(stop) {}
    const std::vector<SignalInfo>& signals() const override { return in_->signals(); }
    Timebase timebase() const override { return in_->timebase(); }
    std::string formatName() const override { return in_->formatName(); }
    std::string wallClockStart() const override { return in_->wallClockStart(); }
    void select(const std::vector<LineRef>& l) override { in_->select(l); }
    std::vector<std::uint8_t> initialLevels() override {
        auto v = in_->initialLevels();
        t0_ = std::chrono::steady_clock::now();
        return v;
    }
    Tick startTick() const override { return in_->startTick(); }
    bool next(EdgeBlock& b) override {
        if (!in_->next(b)) return false;
        Tick last = b.edges.empty() ? b.known_until : b.edges.back().t;
        if (last != kNoTick) {
            const double s = double(last - in_->startTick()) * in_->timebase().secondsPerTick();
            sleepUntil(t0_ + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                 std::chrono::duration<double>(s)));
        }
        return true;
    }
    Tick endTick() const override { return in_->endTick(); }
    std::vector<std::string> notes() const override { return in_->notes(); }
    bool readsVoltages() const override { return in_->readsVoltages(); }
    bool endsAtLastChange() const override { return in_->endsAtLastChange(); }
    std::uint64_t bytesRead() const override { return in_->bytesRead(); }
    std::uint64_t bytesTotal() const override { return in_->bytesTotal(); }

private:
    // In short slices: a stop request (Ctrl-C) ends a long pause at once.
    void sleepUntil(std::chrono::steady_clock::time_point when) const {
        constexpr auto kSlice = std::chrono::milliseconds(20);
        while (!(stop_ && *stop_)) {
            const auto now = std::chrono::steady_clock::now();
            if (now >= when) return;
            std::this_thread::sleep_for(
                std::min<std::chrono::steady_clock::duration>(when - now, kSlice));
        }
    }

    std::unique_ptr<CaptureReader> in_;
    const std::atomic<bool>* stop_;
    std::chrono::steady_clock::time_point t0_;
};

}  // namespace busdecode
