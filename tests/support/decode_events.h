#pragma once
// Decoding in a test: a sink that keeps every event, and a capture file decoded with
// some requests into the events it gave (in the order the session released them).
#include <string>
#include <vector>

#include "capture/capture_reader.h"
#include "core/session.h"

namespace busdecode::test {

struct EventCollector : OutputSink {
    std::vector<Event> events;
    void onEvent(const Event& e, const CaptureFacts&) override { events.push_back(e); }
};

// One that reads the events' fields and never their summaries, as jsonl, verify and
// Python do: decoders may leave the summaries out.
struct FieldCollector : EventCollector {
    bool readsSummaries() const override { return false; }
};

// An in-memory capture decoded for such a sink alone.
std::vector<Event> decodeForFields(const struct Waveform& w,
                                   const std::vector<DecoderRequest>& requests);

// A reader already open (a capture in memory, say), named "memory" in the session.
std::vector<Event> decodeEvents(CaptureReader& reader, std::vector<DecoderRequest> requests,
                                CaptureFacts* facts = nullptr);
// `facts`, if given, gets what the session knew at the end (the timebase, advice).
std::vector<Event> decodeEvents(const std::string& path, std::vector<DecoderRequest> requests,
                                const OpenOptions& open = {}, CaptureFacts* facts = nullptr);

// The events of one type, in order.
std::vector<Event> eventsOfType(const std::vector<Event>& events, const std::string& type);

}  // namespace busdecode::test
