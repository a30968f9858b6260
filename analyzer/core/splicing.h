#pragma once
// Opt-in: a decoder that can be spliced, for decoding a capture in pieces on several
// threads at once (core/piece_speculation.h). A decoder started fresh partway through
// the capture takes over from the one that decoded up to there, from the first point
// where their states are the same. Only a FastDecoder (block_decoding.h) that is also a
// SpliceableDecoder is decoded that way.
#include <cstdint>
#include <vector>

#include "decoder.h"

namespace busdecode {

// What a decoder is at one point of the edge stream. `words` is everything that decides
// what the decoder does with the edges after that point; two decoders with the same
// words there emit the same events from then on. `counts` are running totals (frames
// seen, say) that do not decide anything: the one taking over adds the other's
// (addCounts()).
struct SpliceState {
    std::vector<std::uint64_t> words;
    std::vector<std::uint64_t> counts;
};

class SpliceableDecoder {
public:
    virtual ~SpliceableDecoder() = default;
    // Fills `out` wherever the decoder is at a point it can be compared at (between
    // frames, say), returning false elsewhere: a false costs nothing but a later splice.
    // Every field it leaves out of SpliceState::words must be one that two decoders of
    // the same options given the same edges from that point on cannot differ in.
    virtual bool spliceState(SpliceState& out) const = 0;
    // Called after start() on a decoder started partway through the capture: it may set
    // what it cannot know to what a long capture most likely left (BiSS-C: a preamble of
    // CDM zeros seen), so that its state meets the other's sooner. A wrong guess costs a
    // later splice, never a different output.
    virtual void guessHistory() {}
    // Adds `delta` to SpliceState::counts, element by element (modulo 2^64): this
    // decoder takes over from one whose totals were that much higher.
    virtual void addCounts(const std::vector<std::uint64_t>& delta) = 0;
};

// The SpliceableDecoder behind `d`, or null.
inline SpliceableDecoder* splicingOf(Decoder& d) {
    return dynamic_cast<SpliceableDecoder*>(&d);
}

}  // namespace busdecode
