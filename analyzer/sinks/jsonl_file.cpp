#include "jsonl_file.h"

#include "capture/capture_reader.h"
#include "core/session.h"
#include "event_format.h"

namespace busdecode {

std::string decodeFileToJsonl(const std::string& path, const std::string& proto,
                              const std::map<std::string, std::string>& options) {
    auto reader = openCapture(path, OpenOptions{});
    Session session({DecoderRequest{proto, {}, options}}, *reader, path);
    struct Jsonl : OutputSink {
        std::string text;
        void onEvent(const Event& e, const CaptureFacts& f) override {
            text += eventToJson(e, f.timebase);
            text += '\n';
        }
    } sink;
    session.addSink(&sink);
    session.run();
    return sink.text;
}

std::string goldenPathFor(const std::string& capture) {
    const auto slash = capture.rfind('/');
    const auto dot = capture.rfind('.');
    const bool has_ext = dot != std::string::npos && (slash == std::string::npos || dot > slash);
    return (has_ext ? capture.substr(0, dot) : capture) + ".golden.jsonl";
}

}  // namespace busdecode
