#pragma once
// A frame's rising MA edges: the part of std::vector's interface the BiSS-C decoder uses,
// plus room a run of data edges may append into from its locals. BisscDecoder::dataRun()
// reserves room for the run's rises, keeps the storage and the size in registers, writes
// each rise past size(), and sets the size once when the run ends: a vector would load
// and store its end pointer in memory, and test its capacity, at every rise (two edges in
// five of a frame).
#include <algorithm>
#include <cstddef>
#include <vector>

#include "core/time.h"

namespace busdecode {

class RiseList {
public:
    std::size_t size() const { return size_; }
    bool empty() const { return size_ == 0; }
    Tick front() const { return buf_[0]; }
    Tick back() const { return buf_[size_ - 1]; }
    Tick operator[](std::size_t i) const { return buf_[i]; }

    void push_back(Tick t) {
        if (size_ == buf_.size()) grow();
        buf_[size_++] = t;
    }
    // Drops every rise, keeping the storage (one frame every few microseconds).
    void clear() { size_ = 0; }
    void eraseFirst() {
        for (std::size_t i = 1; i < size_; ++i)
            buf_[i - 1] = buf_[i];
        --size_;
    }

    // For a run that appends from its locals: reserve(n) makes room for n rises in all,
    // data() is the storage, and setSize() then counts the rises written past size().
    void reserve(std::size_t n) {
        if (n > buf_.size()) buf_.resize(std::max(n, 2 * buf_.size()));
    }
    Tick* data() { return buf_.data(); }
    void setSize(std::size_t n) { size_ = n; }
    // The size itself, for a one-edge run bound to the members (BisscDecoder::edge()),
    // which counts its rise in place.
    std::size_t& sizeRef() { return size_; }

private:
    void grow() { buf_.resize(buf_.empty() ? 64 : 2 * buf_.size()); }

    std::vector<Tick> buf_;  // sized to the room; the first size_ are the rises
    std::size_t size_ = 0;
};

}  // namespace busdecode
