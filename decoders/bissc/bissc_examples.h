#pragma once
// The example captures shipped in captures/bissc_*: how each is generated and the
// decoder options that decode it. make_bissc_examples writes them (and their golden
// jsonl); the examples test re-generates them and checks the committed files, the
// decoder's output and the golden files against the generator's truth.
#include <map>
#include <string>
#include <vector>

#include "bissc_generator.h"
#include "capture/capture_writer.h"

namespace busdecode {

struct BisscExample {
    std::string file;  // name in captures/, e.g. "bissc_1mhz_26bit.vcd"
    bool csv = false;  // sigrok dense CSV, else VCD
    std::string description;
    std::map<std::string, std::string> options;  // --opt KEY=VALUE for `decode --proto bissc`
    std::vector<BisscFrameTruth> frames;
    std::vector<ControlEventTruth> control;  // register / command events carried
    Waveform wave;
};

std::vector<BisscExample> bisscExamples();

}  // namespace busdecode
