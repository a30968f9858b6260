#pragma once
// Decodes a capture file the way the CLI does (open it, one session, run) and keeps
// every event, for tests that compare a file's events with a truth.
#include <string>
#include <vector>

#include "core/session.h"

namespace busdecode::test {

// An output that keeps every event in the order the session releases them.
struct EventCollector : OutputSink {
    std::vector<Event> events;
    void onEvent(const Event& e, const CaptureFacts&) override { events.push_back(e); }
};

// Every event of the capture at `path` decoded as `requests` ask.
std::vector<Event> decodeFileEvents(const std::string& path,
                                    const std::vector<DecoderRequest>& requests);

// The events of one type, in order.
std::vector<Event> eventsOfType(const std::vector<Event>& events, const std::string& type);

// captures/FILE in the source tree (the example captures).
std::string examplePath(const std::string& file);

}  // namespace busdecode::test
