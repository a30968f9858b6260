#pragma once
// What a scheduler hands one task of a batch: `--shard K/N` (1-based, K from 1 to N, so
// Slurm's `--array=1-N` passes $SLURM_ARRAY_TASK_ID as is) picks the K-th of N contiguous
// slices of the capture list, and `--from-list FILE` reads that list, one path a line.
#include <cstddef>
#include <string>
#include <vector>

namespace busdecode {

struct Shard {
    std::size_t index = 1;     // K, 1-based
    std::size_t count = 1;     // N
    std::string text() const;  // "K/N"
};

// "3/8" -> {3, 8}. Throws InputError naming `option` unless 1 <= K <= N.
Shard parseShard(const std::string& text, const std::string& option = "--shard");

// [first, last) of `shard` in a list of `total`: contiguous, sizes differ by at most one,
// and the N slices cover 0..total exactly once in order (so merged shards keep the order).
std::pair<std::size_t, std::size_t> shardRange(std::size_t total, const Shard& shard);

std::vector<std::string> shardOf(const std::vector<std::string>& captures, const Shard& shard);

// One capture path a line; blank lines and lines starting with '#' are skipped, a
// trailing '\r' is dropped. Throws InputError naming the file (and line for a NUL byte).
std::vector<std::string> readCaptureList(const std::string& path);

}  // namespace busdecode
