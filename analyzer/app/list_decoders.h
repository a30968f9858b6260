#pragma once
#include <cstdio>

#include "core/decoder_info.h"

namespace busdecode {
// `decode --list`: every decoder's roles, options and event types, from its declaration.
void printDecoderList(std::FILE* out);
// An option's kind as the list names it ("int", "number", "0/1", "choice", "text").
const char* optionKindName(OptionSpec::Kind kind);
}  // namespace busdecode
