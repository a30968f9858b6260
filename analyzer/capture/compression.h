#pragma once
// The compressions a capture may come in, told by their magic bytes.
#include <string_view>

namespace busdecode {

enum class Compression { None, Gzip, Xz, Zstd };

// By the first bytes of the input (at least 6 for xz).
Compression compressionOf(std::string_view head);
const char* compressionName(Compression c);  // "gzip", "xz", "zstd"

}  // namespace busdecode
