#include "decode_capture.h"

#include <memory>

#include "capture/differential_pairs.h"
#include "capture/prefetch_reader.h"
#include "core/registry.h"
#include "paced_reader.h"

namespace busdecode {

CaptureFacts decodeCapture(const std::string& path, const std::vector<DecoderRequest>& requests,
                           const OpenOptions& open, const std::vector<OutputSink*>& sinks) {
    return decodeCapture(path, requests, open, sinks, false, nullptr);
}

namespace {

// The names the session may bind signals by (Session's findSignal): a wide VCD keeps
// only these (OpenOptions::wanted_signals).
std::vector<std::string> wantedSignals(const std::vector<DecoderRequest>& requests) {
    std::vector<std::string> names;
    for (const auto& req : requests) {
        for (const auto& [role, ref] : req.map) {
            names.push_back(ref);
            std::string wire_p, wire_n;  // a differential pair's wires
            if (splitPair(ref, wire_p, wire_n)) names.insert(names.end(), {wire_p, wire_n});
        }
        if (const DecoderFactory* f = Registry::instance().find(req.proto))
            for (const auto& r : f->info().roles) {
                names.push_back(r.name);
                names.insert(names.end(), r.aliases.begin(), r.aliases.end());
            }
    }
    return names;
}

}  // namespace

CaptureFacts decodeCapture(const std::string& path, const std::vector<DecoderRequest>& requests,
                           const OpenOptions& open, const std::vector<OutputSink*>& sinks,
                           bool realtime, const std::atomic<bool>* stop) {
    // Read ahead on a second thread while this one decodes (two cores, pipelined), unless
    // told to keep to one (--threads 1: several decodes side by side, one core each). A
    // file read to its end, never waiting for input, is handed over a few blocks at a
    // time: one whose size the reader knows (a regular file; a pipe's is unknown), not
    // followed.
    // Differential pairs named in --map ("MA+,MA-") become signals of the capture.
    OpenOptions with_pairs = open;
    if (with_pairs.wanted_signals.empty()) with_pairs.wanted_signals = wantedSignals(requests);
    std::string wire_p, wire_n;
    for (const auto& r : requests)
        for (const auto& [role, signal] : r.map)
            if (splitPair(signal, wire_p, wire_n)) with_pairs.pairs.push_back(signal);
    for (auto* s : sinks)
        with_pairs.keep_voltages |= s->wantsEdges();
    std::unique_ptr<CaptureReader> reader = openCapture(path, with_pairs);
    if (!with_pairs.pairs.empty()) reader = pairedReader(std::move(reader), with_pairs.pairs);
    if (open.read_ahead && !reader->readsAhead()) {
        const bool whole_file = !open.follow && reader->bytesTotal() > 0;
        reader =
            prefetchReader(std::move(reader), kReadAheadBlocks, whole_file ? kWholeFileBatch : 1);
    }
    if (realtime) reader = std::make_unique<PacedReader>(std::move(reader), stop);
    Session session(requests, *reader, path);
    session.setPieceSpeculation(open.decode_ahead);
    if (stop) session.setStopFlag(stop);
    if ((!open.thresholds.empty() || open.hysteresis >= 0) && !reader->readsVoltages())
        session.addNote(
            "--threshold and --hysteresis do nothing: the capture's lines are logic levels, not "
            "voltages");
    // Stopped before its end, a capture that is not followed is not reported at all.
    if (stop && !open.follow) session.abandonWhenStopped();
    for (auto* s : sinks)
        session.addSink(s);
    session.run();
    return session.facts();
}

}  // namespace busdecode
