#pragma once
// fstapi (GTKWave's FST library, built by cmake/BusdecodeFstapi.cmake) for the FST reader
// and writer: its fatal errors as exceptions, its file checked before it reads it.
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>

namespace busdecode {

// What fstapi's exit(255) paths throw (a corrupt compressed block): its own message.
class FstApiFatal : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// True when `head` starts as an FST file does: a header block (type 0, 329 bytes), an
// unfinished one (type 255), or a gzip-wrapped file (type 254, then gzip's magic).
bool looksLikeFst(std::string_view head);

// Walks the file's block chain (type byte, big-endian length, payload), inside a gzip
// wrapper too, so that fstapi never reads a truncated or foreign block: throws an
// InputError "`name`: block N ..." for the first that does not fit or is not an FST block.
void checkFstBlocks(const std::string& path, const std::string& name);

// An fstapi reader context, closed on destruction.
struct FstContextCloser {
    void operator()(void* ctx) const;
};
using FstContext = std::unique_ptr<void, FstContextCloser>;

}  // namespace busdecode
