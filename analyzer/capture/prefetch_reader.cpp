#include "prefetch_reader.h"

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <deque>
#include <exception>
#include <mutex>
#include <thread>
#include <utility>

#include <pthread.h>

namespace busdecode {

namespace {

class PrefetchReader : public CaptureReader {
public:
    PrefetchReader(std::unique_ptr<CaptureReader> inner, int ahead, int batch)
        : in_(std::move(inner)),
          ahead_(ahead < 1 ? 1 : std::size_t(ahead)),
          low_water_(ahead_ / 2),
          batch_(std::clamp<std::size_t>(batch < 1 ? 1 : std::size_t(batch), 1, ahead_)) {}
    ~PrefetchReader() override {
        {
            std::lock_guard<std::mutex> lock(m_);
            quit_ = true;
        }
        space_.notify_all();
        if (worker_.joinable()) worker_.join();
    }

    const std::vector<SignalInfo>& signals() const override { return in_->signals(); }
    Timebase timebase() const override { return in_->timebase(); }
    std::string formatName() const override { return in_->formatName(); }
    std::string wallClockStart() const override { return in_->wallClockStart(); }
    void select(const std::vector<LineRef>& lines) override { in_->select(lines); }
    std::vector<std::uint8_t> initialLevels() override { return in_->initialLevels(); }
    Tick startTick() const override { return in_->startTick(); }

    bool next(EdgeBlock& block) override {
        if (!worker_.joinable() && !finished_) worker_ = std::thread([this] { produce(); });
        std::unique_lock<std::mutex> lock(m_);
        if (full_.empty() && !finished_) {
            // A decoder that finds the queue empty sleeps until `batch_` blocks are ready,
            // or one that is not full (the reader ran out of input: its edges must not
            // wait), or the end: one wake-up per batch on the reading thread when it is
            // the slower one.
            consumer_waiting_ = true;
            flush_ = false;
            ready_.wait(lock, [&] { return full_.size() >= batch_ || flush_ || finished_; });
            consumer_waiting_ = false;
        }
        if (full_.empty()) {
            if (error_) std::rethrow_exception(std::exchange(error_, nullptr));
            block.clear();
            return false;
        }
        // Hand the filled block over and give its storage back for reuse.
        std::swap(block, full_.front());
        full_.front().clear();
        spare_.push_back(std::move(full_.front()));
        full_.pop_front();
        // A reader that found the queue full sleeps until it is half empty, not until one
        // block is taken: one wake-up per ahead/2 blocks on the decoding thread when it
        // is the slower one.
        const bool wake = producer_waiting_ && full_.size() <= low_water_;
        lock.unlock();
        if (wake) space_.notify_one();
        return true;
    }
    // Valid once next() has returned false (the worker has finished by then).
    std::vector<std::string> notes() const override { return in_->notes(); }
    bool readsVoltages() const override { return in_->readsVoltages(); }
    bool endsAtLastChange() const override { return in_->endsAtLastChange(); }
    Tick endTick() const override { return in_->endTick(); }
    std::uint64_t bytesRead() const override { return bytes_read_.load(std::memory_order_relaxed); }
    std::uint64_t bytesTotal() const override { return in_->bytesTotal(); }
    bool changesOnly() const override { return in_->changesOnly(); }
    bool readsAhead() const override { return true; }

private:
    void produce() {
        // Named, so that top -H and perf report --sort comm tell the two threads apart.
        pthread_setname_np(pthread_self(), "decode-read");
        EdgeBlock block;
        block.edges.reserve(kEdgeBlockSize);
        try {
            for (;;) {
                const bool more = in_->next(block);
                bytes_read_.store(in_->bytesRead(), std::memory_order_relaxed);
                if (!more) break;
                std::unique_lock<std::mutex> lock(m_);
                if (full_.size() >= ahead_ && !quit_) {
                    producer_waiting_ = true;
                    space_.wait(lock, [&] { return full_.size() <= low_water_ || quit_; });
                    producer_waiting_ = false;
                }
                if (quit_) break;
                if (block.edges.size() < kEdgeBlockSize / 2) flush_ = true;
                full_.push_back(std::move(block));
                if (!spare_.empty()) {
                    block = std::move(spare_.back());
                    spare_.pop_back();
                } else {
                    block = EdgeBlock{};
                    block.edges.reserve(kEdgeBlockSize);
                }
                const bool wake = consumer_waiting_ && (full_.size() >= batch_ || flush_);
                lock.unlock();
                if (wake) ready_.notify_one();
            }
        } catch (...) {
            std::lock_guard<std::mutex> lock(m_);
            error_ = std::current_exception();
        }
        {
            std::lock_guard<std::mutex> lock(m_);
            finished_ = true;
        }
        ready_.notify_one();
    }

    std::unique_ptr<CaptureReader> in_;
    const std::size_t ahead_;
    const std::size_t low_water_;  // a full queue refills from this many blocks
    const std::size_t batch_;      // an empty queue is taken from again at this many
    std::thread worker_;
    std::mutex m_;
    std::condition_variable ready_, space_;
    std::deque<EdgeBlock> full_;
    std::vector<EdgeBlock> spare_;
    std::exception_ptr error_;
    bool finished_ = false;
    bool quit_ = false;
    bool producer_waiting_ = false;  // the reader sleeps on space_
    bool consumer_waiting_ = false;  // the decoder sleeps on ready_
    bool flush_ = false;             // a block short of full came while it slept
    std::atomic<std::uint64_t> bytes_read_{0};
};

}  // namespace

std::unique_ptr<CaptureReader> prefetchReader(std::unique_ptr<CaptureReader> inner, int ahead,
                                              int batch) {
    return std::make_unique<PrefetchReader>(std::move(inner), ahead, batch);
}

}  // namespace busdecode
