#pragma once
// Output files (reports, JUnit) are written atomically: the text goes to a temporary file
// beside the target, which is then renamed over it, so an interrupted run leaves either
// the old file or the complete new one, never half of one.
#include <string>

namespace busdecode {

// Throws InputError naming the file when it cannot be written.
void writeFileAtomically(const std::string& path, const std::string& text);

}  // namespace busdecode
