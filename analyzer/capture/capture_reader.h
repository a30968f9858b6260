#pragma once
// A capture source: VCD, CSV (sigrok dense, Saleae, plain), sigrok .sr, or memory.
// Open parses the header; select() picks the mapped signals; next() streams edges of
// those signals only, in blocks, so memory stays flat whatever the capture length.
#include <atomic>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/edge.h"
#include "core/time.h"

namespace busdecode {

struct SignalInfo {
    std::string name;       // last component ("MA", "clk")
    std::string full_name;  // hierarchical VCD name ("top.enc.clk"), or same as name
    int width = 1;          // vector width (VCD); 1 for logic lines
};

// One selected line: a signal, and for vectors the bit within it (-1 = scalar / bit 0).
struct LineRef {
    int signal = 0;
    int bit = -1;
};

// Work a reader that tokenises pieces of a file on several threads (segmented_vcd_reader.h)
// does on each piece beside the tokenising, on the thread that tokenised it: the session
// decodes the piece there on speculation (core/piece_speculation.h).
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

class CaptureReader {
public:
    virtual ~CaptureReader() = default;
    virtual const std::vector<SignalInfo>& signals() const = 0;
    virtual Timebase timebase() const = 0;
    virtual std::string formatName() const = 0;  // "vcd", "sigrok-csv", "saleae-csv", ...
    // Chooses the lines to deliver; Edge::line indexes this list. Call once before next(),
    // with at most kMaxSelectedLines lines (checkSelection()).
    virtual void select(const std::vector<LineRef>& lines) = 0;
    // Level of each selected line at the capture start. May read ahead; call after select().
    virtual std::vector<std::uint8_t> initialLevels() = 0;
    // First tick of the capture (valid after initialLevels()).
    virtual Tick startTick() const = 0;
    // Fills `block` (cleared first) with up to kEdgeBlockSize edges. False at the end.
    virtual bool next(EdgeBlock& block) = 0;
    // Last tick of the capture: the last timestamp or sample (valid after next() = false).
    virtual Tick endTick() const = 0;
    // Bytes consumed so far and total (0 if unknown), for progress and throughput.
    virtual std::uint64_t bytesRead() const { return 0; }
    virtual std::uint64_t bytesTotal() const { return 0; }
    // What the file says about its traffic beyond its signals (DSView: the protocol
    // decoders set up in it), one line each, for `decode --formats FILE`.
    virtual std::vector<std::string> notes() const { return {}; }
    // True if every edge changes its line's level (the reader drops repeated values
    // itself): the session then skips its own check.
    virtual bool changesOnly() const { return false; }
    // True if next() already reads ahead on a thread of its own (a reader that is not
    // to be wrapped in prefetchReader()).
    virtual bool readsAhead() const { return false; }
    // Asks the reader to run `work` on every piece it tokenises ahead but the first; call
    // before the first next(). False: this reader has no pieces (work is never run).
    // The reader keeps `work` as long as it may still run it.
    virtual bool setPieceWork(std::shared_ptr<PieceWork> work) {
        (void)work;
        return false;
    }
    // After a next() that returned a piece's first block: the work's result for that
    // piece, and how many of its first edges were dropped (PieceWork::Piece). Null
    // otherwise, or when the piece has none; each result is handed out once.
    virtual std::unique_ptr<PieceWork::Result> takePieceResult(std::uint32_t& dropped) {
        (void)dropped;
        return nullptr;
    }
};

// For select(): more lines than an Edge can name is the caller's mistake (Session refuses
// such mappings with an InputError first).
inline void checkSelection(const std::vector<LineRef>& lines) {
    if (lines.size() > kMaxSelectedLines)
        throw std::length_error("CaptureReader::select: more than kMaxSelectedLines lines");
}

struct OpenOptions {
    double rate_hz = 0;   // --rate: needed by plain CSV without a time column
    bool follow = false;  // --follow: keep reading a growing file
    // --threads 2 (the default): decodeCapture() reads ahead on a second thread; false
    // (--threads 1): reads and decodes on the caller's thread alone.
    bool read_ahead = true;
    // With read_ahead: a regular file, not followed, is also read ahead into memory on a
    // third thread (FileReadAhead), so that the kernel's copy runs beside the tokeniser.
    bool read_file_ahead = true;
    // With both: the session may decode the pieces ahead too, on the threads that read
    // them (core/piece_speculation.h). Off where several decodes already keep every
    // core busy (verify --jobs 2 and more): there it only adds work.
    bool decode_ahead = true;
    // With both: a VCD file is read in pieces on two threads (segmented_vcd_reader.h) of
    // this nominal length, the next `#time` line looked for this far past it; 0: the
    // defaults there. Tests and the vcd_pieces fuzz target cut files finer.
    std::uint64_t vcd_piece_bytes = 0;
    std::uint64_t vcd_boundary_search = 0;
    // Set (e.g. by Ctrl-C) to make a following reader return at its next poll.
    const std::atomic<bool>* stop = nullptr;
};

// Picks the reader by content (and extension as a hint). Throws InputError naming the
// file (and line) on anything it cannot read. "-" is standard input.
std::unique_ptr<CaptureReader> openCapture(const std::string& path, const OpenOptions& opts);

// A reader over an in-memory Waveform (tests, generators).
struct Waveform;
std::unique_ptr<CaptureReader> memoryReader(const Waveform& w);

}  // namespace busdecode
