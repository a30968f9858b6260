#pragma once
// The vcd_pieces fuzz target, and what the reader tests share with it: a VCD read in
// pieces on two threads (SegmentedVcdReader) must read as the sequential reader reads it.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>

#include "capture/capture_reader.h"

namespace busdecode::fuzz {

// Options that read a file sequentially on the caller's thread: no read-ahead, no pieces.
OpenOptions sequentialOptions();

// What a reader hands out for the file at `path`, as text: the initial levels and start,
// every edge as it comes (repeats kept), the end and the bytes read; or, where it
// throws an InputError, the edges before it and the error. Every scalar is selected, and
// bits 0, width / 2 and width - 1 of vectors (at most 64 lines). `before_edges` runs
// after the initial levels are read, before the first edge (a test changing the file).
std::string sequentialVcdReading(const std::string& path);
std::string piecesVcdReading(const std::string& path, std::uint64_t piece_bytes,
                             std::uint64_t boundary_search,
                             const std::function<void()>& before_edges = {});

// "" if `got` reads as `want`, else what differs. Where `want` ends in an error, `got`
// must end in the same one, and the edges before it need only agree as far as both go:
// the sequential reader does not hand out the block it was filling when it met the
// fault, so where its blocks end decides how many edges come before the error.
std::string readingDifference(const std::string& got, const std::string& want);

// The target. Input: the piece length (1 + byte 0 % 64), the search for the next `#time`
// line (1 + byte 1 % 64, or 64 KiB from 128 on), then the file.
void runVcdPiecesTarget(const std::uint8_t* data, std::size_t size);

}  // namespace busdecode::fuzz
