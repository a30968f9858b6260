#pragma once
// Readers that cut a file in pieces and tokenise them on several threads
// (segmented_vcd_reader.h) may run more work on each piece, on the thread that tokenised
// it: the session decodes the piece there on speculation (core/parallel_pipeline.h).
// Opt-in beside CaptureReader, which knows nothing of it.
#include <cstdint>
#include <memory>
#include <vector>

#include "core/edge.h"

namespace busdecode {

// The work run on each piece beside the tokenising.
class PieceWork {
public:
    struct Result {
        virtual ~Result() = default;
    };
    // A piece's edges as tokenised, before the piece was joined to the one before it:
    // each line's first edge may repeat the level the line already had (it is then
    // dropped from what next() hands out, and nothing else is).
    struct Piece {
        const EdgeBlock* blocks = nullptr;  // blocks[0, used)
        std::size_t used = 0;
        // Per selected line, the index (block * kEdgeBlockSize + position) of its first
        // edge in the piece, or kNoEdge.
        const std::vector<std::uint32_t>* first_edge = nullptr;
        // The thread running the work: 0, the one that calls next(); 1, the other.
        int thread = 0;
    };
    static constexpr std::uint32_t kNoEdge = ~std::uint32_t(0);

    virtual ~PieceWork() = default;
    // Any thread, several at once. Null: nothing worth handing on. May throw: the piece
    // then has no result, and nothing else changes.
    virtual std::unique_ptr<Result> run(const Piece& piece) = 0;
};

// A CaptureReader that has pieces (found by dynamic_cast, once, before the first next()).
class PieceReader {
public:
    virtual ~PieceReader() = default;
    // Asks the reader to run `work` on every piece it tokenises ahead but the first; call
    // before the first next(). False: this reader has no pieces (work is never run).
    // The reader keeps `work` as long as it may still run it.
    virtual bool setPieceWork(std::shared_ptr<PieceWork> work) = 0;
    // After a next() that returned a piece's first block: the work's result for that
    // piece, and how many of its first edges were dropped (PieceWork::Piece). Null
    // otherwise, or when the piece has none; each result is handed out once.
    virtual std::unique_ptr<PieceWork::Result> takePieceResult(std::uint32_t& dropped) = 0;
};

}  // namespace busdecode
