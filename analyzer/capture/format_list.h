#pragma once
// `decode --formats`: every capture format read, how it is recognised; with files, what
// each one is (format, rate, signals, and what the file says about its traffic).
#include <cstdio>
#include <string>
#include <vector>

#include "capture_reader.h"

namespace busdecode {

struct FormatEntry {
    std::string name;           // as formatName() says it ("dsview-dsl")
    std::string recognised_by;  // what openCapture looks at
    std::string notes;          // what it needs, what it refuses
};
const std::vector<FormatEntry>& captureFormats();

void printFormatList(std::FILE* out);
// Opens `path` (InputError as openCapture) and prints what it is.
void printCaptureDescription(std::FILE* out, const std::string& path, const OpenOptions& opts);

}  // namespace busdecode
