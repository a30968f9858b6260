#pragma once
// Field comparison for LCM tests: an LCM message's value against the event's (or the
// jsonl output's) value, by meaning: integers exactly, doubles to 1e-9 relative, bools
// equal to 0/1, a one-element list equal to its number, null only to null or missing.
#include <string>

#include "core/value.h"

namespace busdecode::test {

// "" when equal, else a description of the difference.
std::string compareValues(const Value& from_lcm, const Value* expected);

}  // namespace busdecode::test
