#pragma once
// The stdout sinks: human text (one line per event, then a per-decoder summary) and
// JSON lines.
#include <cstdio>
#include <map>
#include <memory>
#include <string>

#include "core/session.h"

namespace busdecode {

std::unique_ptr<OutputSink> makeTextSink(std::FILE* out);
// `name_capture`: every line says which capture it came from (several in one call).
std::unique_ptr<OutputSink> makeJsonlSink(std::FILE* out, bool name_capture = false);

}  // namespace busdecode
