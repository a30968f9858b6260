#pragma once
// A decode pass: binds each requested decoder's roles to capture signals, feeds every
// decoder the edges of its lines in one merged time-ordered stream (several buses in
// one pass), applies the glitch filter, releases events in time order and lets
// decoders correlate with each other's events.
#include <atomic>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "capture/capture_reader.h"
#include "decoder.h"
#include "event.h"

namespace busdecode {

struct DecoderRequest {
    std::string proto;                           // decoder id
    std::map<std::string, std::string> map;      // role -> signal name or index
    std::map<std::string, std::string> options;  // key -> value text (glitch_ns included)
};

// What the sinks learn about the capture before the first event.
struct CaptureFacts {
    std::string file;
    std::string format;
    std::string capture_start;  // wall-clock start from the file (ISO 8601), or ""
    Timebase timebase;
    Tick start = 0;
    Tick end = 0;  // known at the end only
    struct Binding {
        std::string proto, instance, role, signal;
        int line = -1;  // Edge::line of the signal's edges (OutputSink::onEdges)
    };
    std::vector<Binding> bindings;
    std::vector<std::string> protos;  // instance names, in --proto order
    // Each instance's options as resolved (defaults applied), for sinks that interpret
    // fields by the layout (the width a position wraps at).
    std::map<std::string, std::map<std::string, std::string>> options;
    std::uint64_t edges = 0;  // edges read on the mapped lines
    std::uint64_t bytes = 0;
    AcquisitionCounts acquisition;  // live acquisitions: updated with every block
    // The decoders' advice at the end (Decoder::advice), each as "instance: text".
    std::vector<std::string> advice;
};

// The sinks: text, jsonl, report, LCM. The session calls begin, then onEvent in time
// order, then end.
class OutputSink {
public:
    virtual ~OutputSink() = default;
    virtual void begin(const CaptureFacts& facts) { (void)facts; }
    virtual void onEvent(const Event& e, const CaptureFacts& facts) = 0;
    virtual void end(const CaptureFacts& facts) { (void)facts; }
    // False for a sink that never reads Event::fields of an event with a summary (text
    // output): with only such sinks, decoders may leave fields out.
    virtual bool readsFields() const { return true; }
    // False for a sink that never reads Event::summary (jsonl, verify's rules, Python's
    // tables; not LCM, whose annotations carry the text line): with only such sinks,
    // decoders may leave the summary out.
    virtual bool readsSummaries() const { return true; }
    // A sink that draws the captured waveform (the HTML report) sees the mapped lines'
    // edges, each block before the events decoded from it.
    virtual bool wantsEdges() const { return false; }
    virtual void onEdges(const Edge* first, const Edge* last) {
        (void)first;
        (void)last;
    }
    // And the analog lines' samples read with them (when the reader hands them on).
    virtual void onVolts(const std::vector<VoltSample>& volts,
                         const std::vector<LineThreshold>& thresholds) {
        (void)volts;
        (void)thresholds;
    }
};

class Session {
public:
    // Binds roles (throws InputError listing the capture's signals when a role can't be
    // bound) and validates options (InputError naming decoder, option and valid values).
    Session(std::vector<DecoderRequest> requests, CaptureReader& reader,
            std::string file_name = "");
    ~Session();
    void addSink(OutputSink* sink) { sinks_.push_back(sink); }
    // Reads the capture's first levels and starts the decoders, after the sinks are added
    // (run() does it first): an InputError here is a capture or an option refused before
    // any edge is decoded (a bit shorter than the capture's tick).
    void start();
    // Reads the whole capture (or follows it) and decodes. Input errors throw InputError.
    void run();
    // Asks a running follow loop to stop at the next block boundary (signal-safe).
    void requestStop();
    // An external flag (set from a SIGINT handler) checked between blocks as well.
    void setStopFlag(const std::atomic<bool>* flag);
    // A stop then makes run() throw Interrupted (core/interrupted.h) without ending the
    // sinks: for a capture read to its end, whose part is not the whole.
    void abandonWhenStopped();
    const CaptureFacts& facts() const { return facts_; }
    // A line for the summary's hints, after the decoders' and the reader's. Call before run().
    void addNote(std::string note) { notes_.push_back(std::move(note)); }
    // Decoding pieces of the capture ahead on the reader's threads (piece_speculation.h),
    // where the reader cuts the file in pieces and the one decoder can be spliced. On by
    // default; the output is the same either way. Call before run().
    void setPieceSpeculation(bool on);
    struct PieceStats {
        std::uint64_t pieces = 0;       // pieces decoded ahead
        std::uint64_t spliced = 0;      // of those, spliced in
        std::uint64_t edges_ahead = 0;  // edges the decoding thread did not decode itself
    };
    PieceStats pieceStats() const;

    struct Impl;

private:
    // run()'s steps.
    void startDecoders();
    // Decodes one block read, `before` edges before it; returns the edges so far.
    std::uint64_t decodeBlock(EdgeBlock& block, std::uint64_t before);
    void endParallelPath();
    void finishDecoders();

    std::unique_ptr<Impl> impl_;
    std::vector<OutputSink*> sinks_;
    CaptureFacts facts_;
    std::vector<std::string> notes_;  // addNote()
    bool started_ = false;            // start()
};

// Test helper: decodes an in-memory capture and returns the events in output order.
std::vector<Event> decodeWaveform(const struct Waveform& w,
                                  const std::vector<DecoderRequest>& requests);

// Splits "bissc.bits" into ("bissc", "bits") when the prefix names a requested decoder.
std::pair<std::string, std::string> splitScopedKey(const std::string& key);

}  // namespace busdecode
