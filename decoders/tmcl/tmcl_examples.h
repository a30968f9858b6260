#pragma once
// The example captures shipped in captures/tmcl_*, in the kit's shape (decoders/kit):
// make_examples writes them; tests/tmcl re-generates them and checks that the committed
// files decode exactly like the in-memory waveform.
#include <vector>

#include "example.h"

namespace busdecode {

using TmclExample = Example<>;

std::vector<TmclExample> tmclExamples();

}  // namespace busdecode
