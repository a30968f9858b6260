#pragma once
// The example captures shipped in captures/tmc8100_*, in the kit's shape (decoders/kit):
// make_examples writes them; tests/tmc8100 re-generates them and checks that the
// committed files decode exactly like the in-memory waveform.
#include <vector>

#include "example.h"

namespace busdecode {

using Tmc8100Example = Example<>;

std::vector<Tmc8100Example> tmc8100Examples();

}  // namespace busdecode
