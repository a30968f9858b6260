#pragma once
// decode() and follow(): one capture decoded on a worker thread into a bounded queue of
// event batches, taken by the Python iterator. Memory stays constant whatever the
// capture's length: the worker waits while the queue is full. No Python in here.
#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <deque>
#include <exception>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "capture/capture_reader.h"
#include "core/session.h"
#include "event_dict.h"

namespace busdecode::py {

struct DecodeJob {
    std::string path;
    std::vector<DecoderRequest> requests;
    OpenOptions open;
    bool realtime = false;
};

class EventStream {
public:
    // Starts decoding. `batch` events are handed over at a time (1 for live input, so
    // that each event comes out as soon as it is decoded).
    EventStream(DecodeJob job, std::size_t batch);
    ~EventStream();
    EventStream(const EventStream&) = delete;
    EventStream& operator=(const EventStream&) = delete;

    enum class Got { Batch, End, Waiting };
    // Waits up to `ms` until the decoders are bound and the first events may come
    // (true), or the decode failed (rethrows its InputError).
    bool waitStarted(int ms);
    // Takes back `out`, the batch handed out last (its events' storage is filled again
    // with later ones), and moves the next batch into it, waiting up to `ms`. At the
    // end, rethrows the decode's error if it had one.
    Got next(std::vector<TimedEvent>& out, int ms);
    // Stops the decode at its next block and discards what is queued.
    void stop();
    // What the session told its sinks so far (at the end: edges, advice).
    CaptureFacts facts();

private:
    class QueueSink;
    void run(DecodeJob job);
    void push(std::vector<TimedEvent>&& batch);
    // A batch handed back by next(), or an empty one.
    std::vector<TimedEvent> takeSpare();

    const std::size_t batch_;
    std::atomic<bool> stop_{false};
    std::mutex mu_;
    std::condition_variable cv_;
    std::deque<std::vector<TimedEvent>> queue_;
    std::vector<std::vector<TimedEvent>> spare_;  // batches handed back, to fill again
    bool started_ = false, done_ = false;
    std::exception_ptr error_;
    CaptureFacts facts_;  // written before started_, read after
    std::thread worker_;
};

}  // namespace busdecode::py
