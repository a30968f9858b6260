#include "live_edge_queue.h"

#include <algorithm>
#include <chrono>

namespace busdecode {

bool LiveEdgeQueue::full() const {
    std::lock_guard lock(mu_);
    return blocks_.size() >= max_blocks_ || queued_edges_ >= max_edges_;
}

void LiveEdgeQueue::push(EdgeBlock& block, std::uint64_t acquired_until) {
    {
        std::lock_guard lock(mu_);
        acquired_until_ = acquired_until;
        queued_edges_ += block.edges.size();
        blocks_.emplace_back();
        blocks_.back().known_until = block.known_until;
        blocks_.back().edges.swap(block.edges);
        blocks_.back().findings.swap(block.findings);
        if (!spares_.empty()) {
            block.edges.swap(spares_.back());
            spares_.pop_back();
        }
    }
    block.clear();
    ready_.notify_one();
}

void LiveEdgeQueue::close(const std::string& error) {
    {
        std::lock_guard lock(mu_);
        closed_ = true;
        if (error_.empty()) error_ = error;
    }
    ready_.notify_all();
}

void LiveEdgeQueue::countDrop(std::uint64_t samples) {
    std::lock_guard lock(mu_);
    counts_.dropped_samples += samples;
    counts_.dropped_packets++;
}

void LiveEdgeQueue::countSamples(std::uint64_t samples) {
    std::lock_guard lock(mu_);
    counts_.samples += samples;
}

bool LiveEdgeQueue::pop(EdgeBlock& out, const std::atomic<bool>* stop) {
    std::unique_lock lock(mu_);
    while (blocks_.empty()) {
        if (closed_ || (stop && *stop)) return false;
        ready_.wait_for(lock, std::chrono::milliseconds(20));
    }
    EdgeBlock& front = blocks_.front();
    const Tick until = front.known_until;
    if (until != kNoTick && acquired_until_ > std::uint64_t(until))
        counts_.max_lag_samples =
            std::max(counts_.max_lag_samples, acquired_until_ - std::uint64_t(until));
    queued_edges_ -= front.edges.size();
    // The consumer's old vector becomes a spare for the producer.
    out.edges.swap(front.edges);
    out.known_until = until;
    out.findings = std::move(front.findings);
    if (front.edges.capacity() && spares_.size() < 8) {
        front.edges.clear();
        spares_.push_back(std::move(front.edges));
    }
    blocks_.pop_front();
    return true;
}

std::string LiveEdgeQueue::error() const {
    std::lock_guard lock(mu_);
    return error_;
}

LiveCounts LiveEdgeQueue::counts() const {
    std::lock_guard lock(mu_);
    return counts_;
}

}  // namespace busdecode
