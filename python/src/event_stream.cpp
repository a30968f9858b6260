#include "event_stream.h"

#include <chrono>

#include "app/decode_args.h"

namespace busdecode::py {

namespace {
// Batches queued before the decoding thread waits: a few thousand events at most.
constexpr std::size_t kQueuedBatches = 8;
// Batches handed back and kept to fill again: one taken for each one handed back.
constexpr std::size_t kSpareBatches = 2;
}  // namespace

class EventStream::QueueSink : public OutputSink {
public:
    explicit QueueSink(EventStream& s) : s_(s) {}
    bool readsSummaries() const override { return false; }  // dicts hold the jsonl fields
    void begin(const CaptureFacts& facts) override {
        std::lock_guard<std::mutex> lock(s_.mu_);
        s_.facts_ = facts;
        s_.started_ = true;
        s_.cv_.notify_all();
    }
    void onEvent(const Event& e, const CaptureFacts& facts) override {
        if (s_.stop_) return;
        TimedEvent& t = used_ < batch_.size() ? batch_[used_] : batch_.emplace_back();
        ++used_;
        t.set(e, facts.timebase.toNs(e.start), facts.timebase.toNs(e.end));
        if (used_ >= s_.batch_) flush();
    }
    void end(const CaptureFacts& facts) override {
        flush();
        std::lock_guard<std::mutex> lock(s_.mu_);
        s_.facts_ = facts;
    }
    void flush() {
        if (used_ == 0) return;
        batch_.resize(used_);  // a batch given back may have held more
        s_.push(std::move(batch_));
        batch_ = s_.takeSpare();
        used_ = 0;
    }

private:
    EventStream& s_;
    std::vector<TimedEvent> batch_;  // [0, used_) filled; the rest storage to fill
    std::size_t used_ = 0;
};

EventStream::EventStream(DecodeJob job, std::size_t batch) : batch_(batch ? batch : 1) {
    job.open.stop = &stop_;
    worker_ = std::thread([this, job = std::move(job)]() mutable { run(std::move(job)); });
}

EventStream::~EventStream() {
    stop();
    worker_.join();
}

void EventStream::run(DecodeJob job) {
    std::exception_ptr error;
    try {
        QueueSink sink(*this);
        decodeCapture(job.path, job.requests, job.open, {&sink}, job.realtime, &stop_);
    } catch (...) {
        // Stopped on request, the decode may throw that it was cut short: no error then.
        if (!stop_) error = std::current_exception();
    }
    std::lock_guard<std::mutex> lock(mu_);
    error_ = error;
    done_ = true;
    cv_.notify_all();
}

void EventStream::push(std::vector<TimedEvent>&& batch) {
    std::unique_lock<std::mutex> lock(mu_);
    cv_.wait(lock, [&] { return stop_ || queue_.size() < kQueuedBatches; });
    if (stop_) return;
    queue_.push_back(std::move(batch));
    cv_.notify_all();
}

bool EventStream::waitStarted(int ms) {
    std::unique_lock<std::mutex> lock(mu_);
    cv_.wait_for(lock, std::chrono::milliseconds(ms), [&] { return started_ || done_; });
    if (done_ && !started_ && error_) std::rethrow_exception(error_);
    return started_ || done_;
}

std::vector<TimedEvent> EventStream::takeSpare() {
    std::lock_guard<std::mutex> lock(mu_);
    if (spare_.empty()) return {};
    std::vector<TimedEvent> batch = std::move(spare_.back());
    spare_.pop_back();
    return batch;
}

EventStream::Got EventStream::next(std::vector<TimedEvent>& out, int ms) {
    std::unique_lock<std::mutex> lock(mu_);
    if (!out.empty() && spare_.size() < kSpareBatches) spare_.push_back(std::move(out));
    out.clear();
    cv_.wait_for(lock, std::chrono::milliseconds(ms), [&] { return !queue_.empty() || done_; });
    if (!queue_.empty()) {
        out = std::move(queue_.front());
        queue_.pop_front();
        cv_.notify_all();
        return Got::Batch;
    }
    if (!done_) return Got::Waiting;
    if (error_) {
        auto e = error_;
        error_ = nullptr;  // raised once
        std::rethrow_exception(e);
    }
    return Got::End;
}

CaptureFacts EventStream::facts() {
    std::lock_guard<std::mutex> lock(mu_);
    return facts_;
}

void EventStream::stop() {
    std::lock_guard<std::mutex> lock(mu_);
    stop_ = true;
    queue_.clear();
    cv_.notify_all();
}

}  // namespace busdecode::py
