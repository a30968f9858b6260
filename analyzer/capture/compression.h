#pragma once
// The compressions a capture may come in, told by their magic bytes, and one rewriting of
// plain text that takes the same path: bare-CR line ends (classic Mac) made "\n".
#include <string_view>

namespace busdecode {

enum class Compression { None, Gzip, Xz, Zstd, CrLineEnds };

// By the first bytes of the input (at least 6 for xz).
Compression compressionOf(std::string_view head);
const char* compressionName(Compression c);  // "gzip", "xz", "zstd", "cr-lines"
// Text whose first line ends in a CR that no LF follows.
bool hasBareCrLineEnds(std::string_view head);

}  // namespace busdecode
