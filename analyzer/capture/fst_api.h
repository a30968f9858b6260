#pragma once
// fstapi (GTKWave's FST library, built by cmake/BusdecodeFstapi.cmake) for the FST reader
// and writer: its fatal errors as exceptions, its file checked before it reads it.
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace busdecode {

// What fstapi's exit(255) paths throw (a corrupt compressed block): its own message.
class FstApiFatal : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// True when `head` starts as an FST file does: a header block (type 0, 329 bytes), an
// unfinished one (type 255), or a gzip-wrapped file (type 254, then gzip's magic).
bool looksLikeFst(std::string_view head);

// The memory fstapi may take to unpack one value-change block (it holds a block's
// changes whole): a block that says it needs more is refused, and the child process
// fstapi runs in (fst_api_process.h) is limited to this much beyond its start.
inline constexpr std::uint64_t kFstBlockBudget = std::uint64_t(256) << 20;

// A value-change block, as the chain walk found it: where, and the times it covers.
struct FstValueBlock {
    int number;              // in the chain, the header block being 0
    std::uint64_t at;        // its byte offset (in the unpacked stream when wrapped)
    std::uint64_t from, to;  // its first and last time
};
struct FstBlockChain {
    std::vector<FstValueBlock> value_blocks;
    std::string where;  // "" or " (inside its gzip wrapper)"
    // "block N at byte B<where>" of the value block holding `time`.
    std::string blockAt(std::uint64_t time) const;
};

// Walks the file's block chain (type byte, big-endian length, payload), inside a gzip
// wrapper too, so that fstapi never reads a truncated or foreign block, nor one that
// says it needs more than kFstBlockBudget to unpack: throws an InputError
// "`name`: FST block N ..." for the first that does not fit or is not an FST block.
FstBlockChain checkFstBlocks(const std::string& path, const std::string& name);

// An fstapi reader context, closed on destruction.
struct FstContextCloser {
    void operator()(void* ctx) const;
};
using FstContext = std::unique_ptr<void, FstContextCloser>;

}  // namespace busdecode
