#pragma once
// The example captures shipped in captures/bissc_*, in the kit's shape (decoders/kit),
// with the generator's frames and control events as their truth: make_examples writes
// them; the examples test re-generates them and checks the committed files, the
// decoder's output and the golden files against the truth.
#include <vector>

#include "bissc_generator.h"
#include "example.h"

namespace busdecode {

struct BisscExampleTruth {
    std::vector<BisscFrameTruth> frames;
    std::vector<ControlEventTruth> control;  // register / command events carried
};
using BisscExample = Example<BisscExampleTruth>;

std::vector<BisscExample> bisscExamples();

}  // namespace busdecode
