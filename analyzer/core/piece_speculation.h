#pragma once
// A capture decoded in pieces on both cores at once. The segmented VCD reader tokenises
// the file's pieces on two threads, but one decoder takes every edge in order, and where
// the decoder is the slower of the two (BiSS-C: about 0.49 s of CPU for a 500 MB
// capture, against 0.30 s of tokenising) one core waits for the other.
//
// So each piece but the first is also decoded on speculation, on the thread that
// tokenised it, by a decoder of its own started fresh at the piece's start, its events
// kept aside. When the decoding thread, in order, comes to that piece, its decoder goes
// on into the piece only as far as the first point where the two decoders' states are
// the same (SpliceableDecoder::spliceState(): between two frames, once the fresh one has seen a
// frame or two and measured what the other carries over): from there the fresh decoder
// has already done the rest of the piece, so it takes over, its events from that point on
// are output, and the rest of the piece is not decoded again. A piece where the states
// never meet is decoded in order as before: the output is the same either way, byte for
// byte, whatever the traffic (tests/piece_speculation_test.cpp).
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "block_decoding.h"
#include "capture/piece_work.h"
#include "decoder.h"
#include "event_pool.h"
#include "options.h"
#include "splicing.h"

namespace busdecode {

// What a piece's speculative decode left: the decoder at the piece's end, every event it
// emitted, and its first few splice points.
struct Speculation final : PieceWork::Result {
    std::unique_ptr<Decoder> decoder;
    std::vector<EventPtr> events;  // in the order emitted
    struct Snapshot {
        std::uint64_t after = 0;  // edges of the piece (as tokenised) taken by then
        std::size_t events = 0;   // events emitted by then
        SpliceState state;
    };
    std::vector<Snapshot> snapshots;
    std::uint64_t edges = 0;  // edges of the piece as tokenised
    Tick last = kNoTick;      // the time of its last edge
};

// The PieceWork of a session with one decoder, handed its edges in blocks.
class PieceSpeculator final : public PieceWork {
public:
    // ctx, hints: the session's decoder's (sink and initial levels are replaced); role_of_line:
    // the session's, line -> role; decoding_pool: where the session gives back the events
    // it is done with (or null), for pieces run on the decoding thread (Piece::thread 0);
    // other_pool: where it gives back those of pieces run on the other thread, marked
    // EventHome 1 (or null: they use decoding_pool too); instance: what the session
    // sets Event::instance to, set here already.
    PieceSpeculator(const DecoderFactory& factory, Options options, DecoderContext ctx,
                    FastPathHints hints, std::vector<int> role_of_line,
                    std::shared_ptr<EventPool> decoding_pool,
                    std::shared_ptr<EventPool> other_pool = nullptr, std::string instance = {});
    std::unique_ptr<Result> run(const Piece& piece) override;

    // Splice points kept per piece. A fresh decoder's state meets the other's once it has
    // seen what the other carries from frame to frame (a frame's measurements, after one
    // frame) and guessed the rest right (SpliceableDecoder::guessHistory()); else once the other's
    // history no longer matters (BiSS-C's run of CDM zeros before a control access: after
    // 14 frames).
    static constexpr std::size_t kSnapshots = 8;
    // Looked for after each of the first kDenseSnapshots pauses, then after every
    // kSparseEvery-th: up to the 20th frame, say.
    static constexpr std::uint64_t kDenseSnapshots = 4;
    static constexpr std::uint64_t kSparseEvery = 4;
    // A splice point is looked for after an edge that follows a pause this many times
    // the shortest gap between two edges so far: a frame starts after one, and looking
    // after every edge would cost more than the rest of the piece's decoding. (Where the
    // guess is wrong, a splice comes later or not at all; the output is the same.)
    static constexpr Tick kPauseGaps = 8;

private:
    // A fresh decoder in `spec`, started with the lines at `level_of_line`, its events
    // going to `sink`; null if it is not a spliceable FastDecoder.
    FastDecoder* startDecoder(Speculation& spec, EventSink& sink,
                              const std::vector<int>& level_of_line) const;

    const DecoderFactory& factory_;
    const Options options_;
    const DecoderContext ctx_;
    const FastPathHints hints_;
    const std::vector<int> role_of_line_;
    const std::shared_ptr<EventPool> decoding_pool_;
    const std::shared_ptr<EventPool> other_pool_;
    const std::string instance_;
};

// The decoding thread's side: takes each piece's Speculation and splices it in.
class SpeculationSplicer {
public:
    struct Stats {
        std::uint64_t pieces = 0;       // pieces that came with a speculation
        std::uint64_t spliced = 0;      // of those, decoded ahead from a splice point on
        std::uint64_t edges_ahead = 0;  // edges not decoded again thanks to that
    };
    // `decoder`: the session's, replaced by each spliced piece's; `sink`: where the
    // spliced-in events go (the session); `role_of_line`: the session's.
    SpeculationSplicer(std::unique_ptr<Decoder>& decoder, EventSink& sink, const int* role_of_line)
        : decoder_(decoder), sink_(sink), role_of_line_(role_of_line) {
        lookUpDecoder();
    }

    // A piece's first block is next, `taken` edges handed out before it: its speculation,
    // `dropped` its first edges not handed out.
    void startPiece(std::unique_ptr<Speculation> s, std::uint64_t taken, std::uint32_t dropped);
    // Decodes the block of edges [first, last), the `taken` edges before it handed out
    // already, through splice points where they fall. False: the decoder that decodes on
    // from here decoded these already (and had its advance() called after them); the
    // caller neither decodes nor advances it for this block.
    bool decode(const Edge* first, const Edge* last, std::uint64_t taken);
    const Stats& stats() const { return stats_; }
    // The last edge's time of the last piece spliced in (kNoTick before any): how far the
    // decoder has decoded, which may be past the blocks handed to decode().
    Tick decodedUntil() const { return decoded_until_; }

private:
    void splice(Speculation::Snapshot& at, const SpliceState& mine);
    // The session's decoder's fast path and splicing, looked up again after each splice.
    void lookUpDecoder();

    std::unique_ptr<Decoder>& decoder_;
    FastDecoder* fast_ = nullptr;
    SpliceableDecoder* splicing_ = nullptr;
    EventSink& sink_;
    const int* role_of_line_;
    std::unique_ptr<Speculation> spec_;
    std::uint64_t base_ = 0;        // where the piece as tokenised starts, in edges handed out
    std::size_t next_ = 0;          // spec_'s next snapshot
    std::uint64_t skip_until_ = 0;  // edges handed out up to here were decoded ahead
    Tick decoded_until_ = kNoTick;
    Stats stats_;
};

}  // namespace busdecode
