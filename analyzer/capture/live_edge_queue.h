#pragma once
// Between the acquisition thread and the decoding one: a bounded queue of edge blocks.
// The acquisition side never waits (a device cannot be paused): when the queue is full a
// whole packet of samples is dropped and counted, and the next block delivered starts with
// the edges that bring every line to its level after the gap, and carries the gap as a
// `samples_dropped` finding (capture_events.h).
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <mutex>
#include <string>
#include <vector>

#include "core/edge.h"

namespace busdecode {

struct LiveCounts {
    std::uint64_t samples = 0;          // acquired from the device
    std::uint64_t dropped_samples = 0;  // in packets dropped because decoding lagged
    std::uint64_t dropped_packets = 0;
    std::uint64_t max_lag_samples = 0;  // worst backlog between acquisition and decoding
};

class LiveEdgeQueue {
public:
    // At most `max_blocks` blocks and `max_edges` edges waiting (sparse traffic makes many
    // small blocks, dense traffic few full ones).
    LiveEdgeQueue(std::size_t max_blocks, std::size_t max_edges)
        : max_blocks_(max_blocks), max_edges_(max_edges) {}

    // Producer: no room for another packet's blocks?
    bool full() const;
    // Producer: hands over a filled block (its vector swapped with a spare one).
    void push(EdgeBlock& block, std::uint64_t acquired_until);
    // Producer: no more blocks; `error` ("" = a normal end) is what next() reports.
    void close(const std::string& error = {});
    void countDrop(std::uint64_t samples);
    void countSamples(std::uint64_t samples);

    // Consumer: the next block into `out` (false at the end, or when *stop becomes true).
    // Waits in short slices so that a stop request is seen at once.
    bool pop(EdgeBlock& out, const std::atomic<bool>* stop);
    std::string error() const;
    LiveCounts counts() const;

private:
    mutable std::mutex mu_;
    std::condition_variable ready_;
    std::size_t max_blocks_, max_edges_;
    std::size_t queued_edges_ = 0;
    std::deque<EdgeBlock> blocks_;
    std::vector<std::vector<Edge>> spares_;  // recycled vectors: no allocation per block
    std::uint64_t acquired_until_ = 0;       // ticks acquired so far (for the lag)
    bool closed_ = false;
    std::string error_;
    LiveCounts counts_;
};

}  // namespace busdecode
