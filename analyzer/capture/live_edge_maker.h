#pragma once
// Turns an analyser's sample words into edges of the selected lines, on the acquisition
// thread: only transitions are kept, whatever the sample rate. Blocks go to a
// LiveEdgeQueue as they fill and at the end of every packet (so the decoder's time
// advances with the device's even when nothing changes).
#include <array>
#include <cstdint>
#include <vector>

#include "live_edge_queue.h"

namespace busdecode {

class LiveEdgeMaker {
public:
    // bits[i]: the bit of selected line i in a sample word (0 .. 63).
    void select(const std::vector<int>& bits);
    // At most `samples` samples in all (0 = no limit).
    void setLimit(std::uint64_t samples) { limit_ = samples; }

    // Converts a packet of n words of `unit` bytes and hands its blocks to `queue`.
    // Returns how many samples it took (fewer than n when the limit was reached).
    std::size_t addPacket(const std::uint8_t* data, std::size_t n, unsigned unit,
                          LiveEdgeQueue& queue);
    // A packet the queue has no room for: counted, its levels remembered, no edges.
    std::size_t dropPacket(const std::uint8_t* data, std::size_t n, unsigned unit,
                           LiveEdgeQueue& queue);

    bool started() const { return started_; }
    bool limitReached() const { return limit_ && tick_ >= limit_; }
    std::uint64_t samples() const { return tick_; }
    // Levels of the selected lines at the first sample (valid once started()).
    std::vector<std::uint8_t> initialLevels() const;

private:
    std::size_t take(std::size_t n) const;
    void start(std::uint64_t first_word);
    void emitChanges(std::uint64_t changed, std::uint64_t word, Tick t);
    void flush(LiveEdgeQueue& queue);
    // Edges of n samples from prev_ on; Unit 0: words of `unit` bytes.
    template <unsigned Unit>
    void scan(const std::uint8_t* data, std::size_t n, LiveEdgeQueue& queue, unsigned unit = Unit);

    std::vector<int> bits_;
    std::array<std::vector<std::uint32_t>, 64> lines_of_bit_;
    std::uint64_t mask_ = 0;
    std::uint64_t limit_ = 0;
    std::uint64_t tick_ = 0;  // samples seen so far: the next sample's tick
    std::uint64_t first_ = 0, prev_ = 0;
    std::uint64_t delivered_ = 0;  // levels as the decoder last saw them (after a drop)
    bool started_ = false, gap_ = false;
    Tick gap_first_ = 0;             // the gap's first dropped sample
    std::uint64_t gap_samples_ = 0;  // dropped in the gap so far
    EdgeBlock block_;
};

// A sample word of `unit` bytes (1 to 8), little-endian.
inline std::uint64_t sampleWord(const std::uint8_t* p, unsigned unit) {
    std::uint64_t w = 0;
    for (unsigned i = 0; i < unit; ++i)
        w |= std::uint64_t(p[i]) << (8 * i);
    return w;
}

}  // namespace busdecode
