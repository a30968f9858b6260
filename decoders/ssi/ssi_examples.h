#pragma once
// The example captures shipped in captures/ssi_*, in the kit's shape (decoders/kit), with
// the generator's frames as their truth: make_examples writes them; the examples test
// re-generates them and checks the files and the decoder's output against the truth.
#include <vector>

#include "example.h"
#include "ssi_generator.h"

namespace busdecode {

using SsiExample = Example<std::vector<SsiTruth>>;

std::vector<SsiExample> ssiExamples();

}  // namespace busdecode
