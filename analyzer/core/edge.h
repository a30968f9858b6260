#pragma once
// The transition-stream model: readers turn samples into level changes of the mapped
// lines only, merged in time order and handed out in fixed-size blocks, so memory stays
// flat whatever the capture length.
#include <cstdint>
#include <vector>

#include "time.h"

namespace busdecode {

struct Edge {
    // Left uninitialised by default: a reader sizes a block to kEdgeBlockSize and fills
    // it through a pointer, without first zeroing 256 KiB per block.
    Edge() noexcept {}  // NOLINT: deliberately not `= default` (that would zero on resize)
    constexpr Edge(Tick t_, std::uint32_t line_, std::uint8_t level_) noexcept
        : t(t_), line(line_), level(level_) {}

    Tick t;
    std::uint32_t line;  // index into the reader's selected-line list
    std::uint8_t level;  // 0 or 1, the level *after* the edge
};

struct EdgeBlock {
    std::vector<Edge> edges;  // time ordered; ties keep reader order
    // Time up to which the capture is known to be complete (>= last edge). Lets
    // decoders close frames on timeouts while a followed file is still growing.
    Tick known_until = kNoTick;
    void clear() {
        edges.clear();
        known_until = kNoTick;
    }
};

inline constexpr std::size_t kEdgeBlockSize = 16384;

}  // namespace busdecode
