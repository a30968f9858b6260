#include "decode_facts.h"

#include "capture/capture_reader.h"
#include "paths.h"

namespace busdecode::test {

CaptureFacts decodeCaptureFacts(const std::string& capture_file, const DecoderRequest& request) {
    const std::string path = sourceDir() + "/captures/" + capture_file;
    auto reader = openCapture(path, OpenOptions{});
    Session session({request}, *reader, path);
    session.run();
    return session.facts();
}

}  // namespace busdecode::test
