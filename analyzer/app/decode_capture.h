#pragma once
// Decoding one capture file: the entry point of `decode`, `decode verify` and whoever
// embeds busdecode (open, read ahead, decode into the sinks).
#include <atomic>
#include <string>
#include <vector>

#include "capture/capture_reader.h"
#include "core/session.h"

namespace busdecode {

// Opens one capture and decodes it into the sinks. Throws InputError on bad input.
CaptureFacts decodeCapture(const std::string& path, const std::vector<DecoderRequest>& requests,
                           const OpenOptions& open, const std::vector<OutputSink*>& sinks);
// The same, optionally paced at the capture's own time scale (--realtime) and stopped
// between blocks when *stop becomes true (Ctrl-C): a followed capture then ends as if
// it ended there; any other throws Interrupted (core/interrupted.h), its sinks not ended.
CaptureFacts decodeCapture(const std::string& path, const std::vector<DecoderRequest>& requests,
                           const OpenOptions& open, const std::vector<OutputSink*>& sinks,
                           bool realtime, const std::atomic<bool>* stop);

}  // namespace busdecode
