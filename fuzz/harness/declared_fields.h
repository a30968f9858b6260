#pragma once
// Every field of an event declared by its decoder (DecoderInfo::events) with a value of
// the declared kind: what `decode --list` promises and read()'s column types rely on.
#include <string>
#include <vector>

#include "core/session.h"

namespace busdecode::fuzz {

// Empty when every field of `e` is declared with its kind, else what is not, in a line.
// `requests` are the run's: their options name the fields of a "<option>" declaration.
std::string undeclaredField(const Event& e, const std::vector<DecoderRequest>& requests);

}  // namespace busdecode::fuzz
