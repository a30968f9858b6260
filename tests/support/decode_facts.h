#pragma once
// Decodes a committed capture (captures/FILE) with one decoder request, no output, and
// returns what the session knows at the end: the decoders' advice, the edge count.
#include <string>

#include "core/session.h"

namespace busdecode::test {

CaptureFacts decodeCaptureFacts(const std::string& capture_file, const DecoderRequest& request);

}  // namespace busdecode::test
