#pragma once
// The transition-stream model: readers turn samples into level changes of the mapped
// lines only, merged in time order and handed out in fixed-size blocks, so memory stays
// flat whatever the capture length.
#include <cstdint>
#include <vector>

#include "time.h"

namespace busdecode {

struct Edge {
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
