#include "live_edge_maker.h"

#include <bit>

#include "capture_events.h"

namespace busdecode {

void LiveEdgeMaker::select(const std::vector<int>& bits) {
    bits_ = bits;
    mask_ = 0;
    for (auto& l : lines_of_bit_)
        l.clear();
    for (std::size_t i = 0; i < bits.size(); ++i) {
        lines_of_bit_[std::size_t(bits[i])].push_back(std::uint32_t(i));
        mask_ |= std::uint64_t(1) << bits[i];
    }
}

std::vector<std::uint8_t> LiveEdgeMaker::initialLevels() const {
    std::vector<std::uint8_t> levels;
    for (int b : bits_)
        levels.push_back(std::uint8_t((first_ >> b) & 1u));
    return levels;
}

std::size_t LiveEdgeMaker::take(std::size_t n) const {
    if (!limit_) return n;
    return tick_ >= limit_ ? 0 : std::size_t(std::min<std::uint64_t>(n, limit_ - tick_));
}

void LiveEdgeMaker::start(std::uint64_t first_word) {
    started_ = true;
    first_ = prev_ = delivered_ = first_word & mask_;
}

void LiveEdgeMaker::emitChanges(std::uint64_t changed, std::uint64_t word, Tick t) {
    while (changed) {
        const int bit = std::countr_zero(changed);
        changed &= changed - 1;
        for (std::uint32_t line : lines_of_bit_[std::size_t(bit)])
            block_.edges.emplace_back(t, line, std::uint8_t((word >> bit) & 1u));
    }
}

void LiveEdgeMaker::flush(LiveEdgeQueue& queue) {
    block_.known_until = tick_ ? Tick(tick_ - 1) : 0;
    queue.push(block_, tick_);
}

template <unsigned Unit>
void LiveEdgeMaker::scan(const std::uint8_t* data, std::size_t n, LiveEdgeQueue& queue,
                         unsigned unit) {
    if (Unit) unit = Unit;
    std::uint64_t prev = prev_;
    for (std::size_t i = 0; i < n; ++i) {
        const std::uint64_t w = sampleWord(data + i * unit, unit) & mask_;
        if (w == prev) continue;
        if (block_.edges.size() + bits_.size() > kEdgeBlockSize) {
            block_.known_until = block_.edges.back().t;
            queue.push(block_, tick_ + i);
        }
        emitChanges(w ^ prev, w, Tick(tick_ + i));
        prev = w;
    }
    prev_ = prev;
}

std::size_t LiveEdgeMaker::addPacket(const std::uint8_t* data, std::size_t n, unsigned unit,
                                     LiveEdgeQueue& queue) {
    n = take(n);
    if (n == 0) return 0;
    if (!started_) start(sampleWord(data, unit));
    // After a dropped packet the lines jump to where the device is now, at this tick,
    // which no event reaching into the gap can be trusted across.
    if (gap_) {
        block_.findings.push_back(samplesDroppedEvent(gap_first_, Tick(tick_), gap_samples_));
        emitChanges(delivered_ ^ prev_, prev_, Tick(tick_));
        gap_ = false;
    }
    // The common word widths with the width known to the compiler (one load a sample).
    switch (unit) {
        case 1:
            scan<1>(data, n, queue);
            break;
        case 2:
            scan<2>(data, n, queue);
            break;
        case 4:
            scan<4>(data, n, queue);
            break;
        default:
            scan<0>(data, n, queue, unit);
            break;
    }
    delivered_ = prev_;
    tick_ += n;
    queue.countSamples(n);
    flush(queue);
    return n;
}

std::size_t LiveEdgeMaker::dropPacket(const std::uint8_t* data, std::size_t n, unsigned unit,
                                      LiveEdgeQueue& queue) {
    n = take(n);
    if (n == 0) return 0;
    if (!started_) start(sampleWord(data, unit));
    if (!gap_) {
        delivered_ = prev_;
        gap_first_ = Tick(tick_);
        gap_samples_ = 0;
    }
    gap_ = true;
    gap_samples_ += n;
    prev_ = sampleWord(data + (n - 1) * unit, unit) & mask_;
    tick_ += n;
    queue.countSamples(n);
    queue.countDrop(n);
    return n;
}

}  // namespace busdecode
