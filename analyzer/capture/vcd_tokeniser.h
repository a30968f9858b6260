#pragma once
// What the VCD reader offers SegmentedVcdReader (segmented_vcd_reader.h): its tokeniser
// run over one piece of the value-change section at a time, from a given state, on any
// thread, and a way back to plain sequential reading from any line start.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "capture_reader.h"

namespace busdecode {

// The tokeniser's state between two pieces of the value changes.
struct VcdTokenState {
    // Per selected line: 0 or 1, or kUnknownLevel for a piece tokenised without knowing
    // what came before it (every first change of that line is then an edge).
    std::vector<std::uint8_t> level;
    Tick cur = 0;               // the time in force
    bool seen_time = false;     // false: the piece's first `#time` sets `cur` (first_time)
    bool in_block = false;      // inside a `$comment ... $end`
    std::uint64_t line = 0;     // number of the line the piece starts in (0: counted from 0)
    Tick first_time = kNoTick;  // out: the piece's first time, when seen_time was false
    // Changes of selected lines to x z u w - (levels kept), counted for the summary.
    std::uint64_t unknown_states = 0;
};
inline constexpr std::uint8_t kUnknownLevel = 2;

class VcdTokeniser : public CaptureReader {
public:
    // A tokeniser for another thread: the same header and selection (call after
    // select()), a state of its own, no input (tokenise() only).
    virtual std::unique_ptr<VcdTokeniser> clone() const = 0;
    // Tokenises the bytes [b, e) (whole lines, except a last line at the end of the file)
    // from `state`, which it leaves as it is at `e`. Edges go into blocks[used...] (added
    // as needed), each block cut at kEdgeBlockSize edges with its known_until set; `used`
    // counts the blocks with edges. Throws InputError as the sequential reader would,
    // naming state.line plus the lines before.
    virtual void tokenise(const char* b, const char* e, VcdTokenState& state,
                          std::vector<EdgeBlock>& blocks, std::size_t& used) = 0;
    // After initialLevels(), unless the capture ended there: the file offset where the
    // value changes go on (kNoOffset: not known, read on with next()), and the state there.
    static constexpr std::uint64_t kNoOffset = ~std::uint64_t(0);
    virtual std::uint64_t resumeOffset() const = 0;
    virtual VcdTokenState resumeState() const = 0;
    // Goes on reading sequentially (next()) from `offset` (a line start) in `state`.
    virtual void resumeAt(std::uint64_t offset, const VcdTokenState& state) = 0;
    // The pieces ended in `state` (no resumeAt() followed): what notes() counts.
    virtual void finishedAt(const VcdTokenState& state) = 0;
    // The file being read (a regular file), for pread() on other threads.
    virtual int fileDescriptor() const = 0;
    virtual const std::string& fileName() const = 0;
};

class TextSource;
// The plain (sequential) VCD reader over `src`: what openVcd() returns for input that is
// not cut into pieces, and what SegmentedVcdReader works with.
std::unique_ptr<VcdTokeniser> openVcdTokeniser(std::unique_ptr<TextSource> src,
                                               const OpenOptions& opts);

}  // namespace busdecode
