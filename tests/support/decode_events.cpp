#include "decode_events.h"

#include "capture/capture_reader.h"
#include "core/waveform.h"

namespace busdecode::test {

namespace {
std::vector<Event> run(CaptureReader& reader, std::vector<DecoderRequest> requests,
                       const std::string& name, CaptureFacts* facts, EventCollector&& sink = {}) {
    Session session(std::move(requests), reader, name);
    session.addSink(&sink);
    session.run();
    if (facts) *facts = session.facts();
    return std::move(sink.events);
}
}  // namespace

std::vector<Event> decodeEvents(CaptureReader& reader, std::vector<DecoderRequest> requests,
                                CaptureFacts* facts) {
    return run(reader, std::move(requests), "memory", facts);
}

std::vector<Event> decodeEvents(const std::string& path, std::vector<DecoderRequest> requests,
                                const OpenOptions& open, CaptureFacts* facts) {
    auto reader = openCapture(path, open);
    return run(*reader, std::move(requests), path, facts);
}

std::vector<Event> decodeForFields(const Waveform& w, const std::vector<DecoderRequest>& requests) {
    auto reader = memoryReader(w);
    return run(*reader, requests, "memory", nullptr, FieldCollector{});
}

std::vector<Event> eventsOfType(const std::vector<Event>& events, const std::string& type) {
    std::vector<Event> out;
    for (const Event& e : events)
        if (e.type == type) out.push_back(e);
    return out;
}

}  // namespace busdecode::test
