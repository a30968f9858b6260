#include "prefetch_reader.h"

#include <atomic>
#include <condition_variable>
#include <deque>
#include <exception>
#include <mutex>
#include <thread>
#include <utility>

namespace busdecode {

namespace {

class PrefetchReader : public CaptureReader {
public:
    PrefetchReader(std::unique_ptr<CaptureReader> inner, int ahead)
        : in_(std::move(inner)), ahead_(ahead < 1 ? 1 : std::size_t(ahead)) {}
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
    void select(const std::vector<LineRef>& lines) override { in_->select(lines); }
    std::vector<std::uint8_t> initialLevels() override { return in_->initialLevels(); }
    Tick startTick() const override { return in_->startTick(); }

    bool next(EdgeBlock& block) override {
        if (!worker_.joinable() && !finished_) worker_ = std::thread([this] { produce(); });
        std::unique_lock<std::mutex> lock(m_);
        ready_.wait(lock, [&] { return !full_.empty() || finished_; });
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
        lock.unlock();
        space_.notify_one();
        return true;
    }
    // Valid once next() has returned false (the worker has finished by then).
    Tick endTick() const override { return in_->endTick(); }
    std::uint64_t bytesRead() const override { return bytes_read_.load(std::memory_order_relaxed); }
    std::uint64_t bytesTotal() const override { return in_->bytesTotal(); }
    bool changesOnly() const override { return in_->changesOnly(); }

private:
    void produce() {
        EdgeBlock block;
        block.edges.reserve(kEdgeBlockSize);
        try {
            for (;;) {
                const bool more = in_->next(block);
                bytes_read_.store(in_->bytesRead(), std::memory_order_relaxed);
                if (!more) break;
                std::unique_lock<std::mutex> lock(m_);
                space_.wait(lock, [&] { return full_.size() < ahead_ || quit_; });
                if (quit_) break;
                full_.push_back(std::move(block));
                if (!spare_.empty()) {
                    block = std::move(spare_.back());
                    spare_.pop_back();
                } else {
                    block = EdgeBlock{};
                    block.edges.reserve(kEdgeBlockSize);
                }
                lock.unlock();
                ready_.notify_one();
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
    std::thread worker_;
    std::mutex m_;
    std::condition_variable ready_, space_;
    std::deque<EdgeBlock> full_;
    std::vector<EdgeBlock> spare_;
    std::exception_ptr error_;
    bool finished_ = false;
    bool quit_ = false;
    std::atomic<std::uint64_t> bytes_read_{0};
};

}  // namespace

std::unique_ptr<CaptureReader> prefetchReader(std::unique_ptr<CaptureReader> inner, int ahead) {
    return std::make_unique<PrefetchReader>(std::move(inner), ahead);
}

}  // namespace busdecode
