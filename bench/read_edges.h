#pragma once
// A capture read through its tokeniser alone, nothing decoded: what read_capture and the
// readFile micro-benchmarks time, and what read_capture --edges prints to compare two
// builds' readers.
#include <cinttypes>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "capture/capture_reader.h"
#include "capture/prefetch_reader.h"

namespace busdecode::bench {

// The capture opened with every signal selected, or only signal `only` (>= 0). Throws as
// openCapture and the reader do.
inline std::unique_ptr<CaptureReader> openSelected(const std::string& path, const OpenOptions& opts,
                                                   int only = -1) {
    auto reader = openCapture(path, opts);
    std::vector<LineRef> lines;
    if (only >= 0)
        lines.push_back({only, -1});
    else
        // Every signal, up to the most an Edge can name.
        for (int i = 0; i < int(reader->signals().size()) && lines.size() < kMaxSelectedLines; ++i)
            lines.push_back({i, -1});
    reader->select(lines);
    return reader;
}

// Reads the whole file and returns the number of edges.
inline std::uint64_t readEdges(const std::string& path, int only = -1) {
    OpenOptions one_thread;  // the tokeniser alone: no thread reads the file ahead of it
    one_thread.read_file_ahead = false;
    auto reader = openSelected(path, one_thread, only);
    (void)reader->initialLevels();
    EdgeBlock block;
    std::uint64_t edges = 0;
    while (reader->next(block))
        edges += block.edges.size();
    return edges;
}

struct Touched {
    std::uint64_t edges = 0;
    std::uint64_t checksum = 0;  // of every edge's fields, so that each one is read
};

// Reads the whole file as decode does, with two threads (a VCD in pieces on both,
// SegmentedVcdReader; other formats on a second thread, prefetchReader with decode's
// read-ahead), and reads every edge handed over.
inline Touched readEdgesAhead(const std::string& path) {
    auto reader = openSelected(path, {});
    if (!reader->readsAhead())
        reader = prefetchReader(std::move(reader), kReadAheadBlocks, kWholeFileBatch);
    (void)reader->initialLevels();
    EdgeBlock block;
    Touched out;
    while (reader->next(block)) {
        out.edges += block.edges.size();
        for (const Edge& e : block.edges)
            out.checksum += std::uint64_t(e.t) ^ e.line ^ e.level;
    }
    return out;
}

// Everything the reader hands a decoder, as text: the format, the start tick and the
// initial levels, one "TICK LINE LEVEL" per edge, the end tick. Where the blocks end
// (known_until) is left out: it may move without changing what was read.
inline void printEdges(const std::string& path, const OpenOptions& opts, std::FILE* out) {
    auto reader = openSelected(path, opts);
    const std::vector<std::uint8_t> initial = reader->initialLevels();
    std::fprintf(out, "%s start %" PRId64 " initial", reader->formatName().c_str(),
                 std::int64_t(reader->startTick()));
    for (const std::uint8_t level : initial)
        std::fprintf(out, " %d", int(level));
    std::fputc('\n', out);
    EdgeBlock block;
    while (reader->next(block))
        for (const Edge& e : block.edges)
            std::fprintf(out, "%" PRId64 " %u %u\n", std::int64_t(e.t), unsigned(e.line),
                         unsigned(e.level));
    std::fprintf(out, "end %" PRId64 "\n", std::int64_t(reader->endTick()));
}

}  // namespace busdecode::bench
