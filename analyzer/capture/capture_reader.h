#pragma once
// A capture source: VCD, CSV (sigrok dense, Saleae, plain), sigrok .sr, or memory.
// Open parses the header; select() picks the mapped signals; next() streams edges of
// those signals only, in blocks, so memory stays flat whatever the capture length.
#include <atomic>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "core/edge.h"
#include "core/time.h"

namespace busdecode {

// A live acquisition's sample counts (capture/live_reader.h); all zero for a file.
struct AcquisitionCounts {
    std::uint64_t samples = 0;  // acquired from the analyser
    std::uint64_t dropped = 0;  // dropped, whole packets, because decoding fell behind
    std::uint64_t behind = 0;   // the worst backlog between acquiring and decoding
};

struct SignalInfo {
    std::string name;       // last component ("MA", "clk")
    std::string full_name;  // hierarchical VCD name ("top.enc.clk"), or same as name
    int width = 1;          // vector width (VCD); 1 for logic lines
    // A vector's declared index range (vector_range.h); -1: none, bits 0 .. width-1.
    int msb = -1, lsb = -1;
};

// One selected line: a signal, and for vectors the bit within it (-1 = scalar / bit 0).
struct LineRef {
    int signal = 0;
    int bit = -1;
};

class CaptureReader {
public:
    virtual ~CaptureReader() = default;
    virtual const std::vector<SignalInfo>& signals() const = 0;
    virtual Timebase timebase() const = 0;
    virtual std::string formatName() const = 0;  // "vcd", "sigrok-csv", "saleae-csv", ...
    // When the capture began by the wall clock, as the file says (wall_clock.h), or "".
    virtual std::string wallClockStart() const { return {}; }
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
    // True if every edge changes its line's level (the reader drops repeated values
    // itself): the session then skips its own check.
    virtual bool changesOnly() const { return false; }
    // A live acquisition's counts so far (valid between next() calls).
    virtual AcquisitionCounts acquisition() const { return {}; }
    // True if next() already reads ahead on a thread of its own (a reader that is not
    // to be wrapped in prefetchReader()).
    virtual bool readsAhead() const { return false; }
    // What the reader chose or found that the user should see in the summary (thresholds
    // of analog lines, lines that never crossed them; a DSView session's decoder settings,
    // also shown by `decode --formats FILE`); valid after next() = false.
    virtual std::vector<std::string> notes() const { return {}; }
    // True for a reader of analog lines: --threshold and --hysteresis apply to it.
    virtual bool readsVoltages() const { return false; }
    // True when the capture's end is only its last change: the file records changes but
    // not where the acquisition stopped (a Saleae CSV).
    virtual bool endsAtLastChange() const { return false; }
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
    // The names a decode may look signals up by (--map values, the decoders' role names
    // and aliases; case-insensitive). A VCD declaring more than kKeepAllSignals keeps only
    // the signals named so (memory bounded by what is mapped); empty: keep every signal.
    std::vector<std::string> wanted_signals;
    // Set (e.g. by Ctrl-C) to make a following reader return at its next poll.
    const std::atomic<bool>* stop = nullptr;
    // Analog lines (scope captures): --threshold VOLTS for every line ("" signal) or
    // SIGNAL=VOLTS, --hysteresis VOLTS (< 0: a tenth of the swing); unset: from the data.
    std::vector<std::pair<std::string, double>> thresholds;
    double hysteresis = -1;
    // Analog readers hand their samples on with the edges (EdgeBlock::volts), for a
    // sink that draws the voltage trace (the HTML report).
    bool keep_voltages = false;
    // Differential pairs named in --map ("MA+,MA-"): each becomes a signal of that name.
    std::vector<std::string> pairs;
};

// Picks the reader by content (and extension as a hint). Throws InputError naming the
// file (and line) on anything it cannot read. "-" is standard input.
std::unique_ptr<CaptureReader> openCapture(const std::string& path, const OpenOptions& opts);

// A reader over an in-memory Waveform (tests, generators).
struct Waveform;
std::unique_ptr<CaptureReader> memoryReader(const Waveform& w);

}  // namespace busdecode
