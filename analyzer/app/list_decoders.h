#pragma once
#include <cstdio>

namespace busdecode {
// `decode --list`: every decoder's roles, options and event types, from its declaration.
void printDecoderList(std::FILE* out);
}  // namespace busdecode
