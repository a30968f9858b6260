#pragma once
// --report FILE: a text (.txt or anything else) or self-contained HTML (.html/.htm)
// report a test engineer can file. Written atomically at the end of the pass.
#include <memory>
#include <string>

#include "core/session.h"

namespace busdecode {

std::unique_ptr<OutputSink> makeReportSink(const std::string& path);

}  // namespace busdecode
