#include "decode_file.h"

#include "capture/capture_reader.h"
#include "paths.h"

namespace busdecode::test {

std::vector<Event> decodeFileEvents(const std::string& path,
                                    const std::vector<DecoderRequest>& requests) {
    auto reader = openCapture(path, OpenOptions{});
    Session session(requests, *reader, path);
    EventCollector sink;
    session.addSink(&sink);
    session.run();
    return std::move(sink.events);
}

std::vector<Event> eventsOfType(const std::vector<Event>& events, const std::string& type) {
    std::vector<Event> out;
    for (const auto& e : events)
        if (e.type == type) out.push_back(e);
    return out;
}

std::string examplePath(const std::string& file) {
    return sourceDir() + "/captures/" + file;
}

}  // namespace busdecode::test
