#pragma once
// A capture read through its tokeniser alone, nothing decoded: what read_capture and the
// readFile micro-benchmarks time.
#include <cstdint>
#include <string>
#include <vector>

#include "capture/capture_reader.h"

namespace busdecode::bench {

// Reads the whole file with every signal selected, or only signal `only` (>= 0), and
// returns the number of edges. Throws as openCapture and the reader do.
inline std::uint64_t readEdges(const std::string& path, int only = -1) {
    auto reader = openCapture(path, {});
    std::vector<LineRef> lines;
    if (only >= 0)
        lines.push_back({only, -1});
    else
        for (int i = 0; i < int(reader->signals().size()); ++i)
            lines.push_back({i, -1});
    reader->select(lines);
    (void)reader->initialLevels();
    EdgeBlock block;
    std::uint64_t edges = 0;
    while (reader->next(block))
        edges += block.edges.size();
    return edges;
}

}  // namespace busdecode::bench
