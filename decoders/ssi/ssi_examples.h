#pragma once
// The example captures shipped in captures/ssi_*: how each is generated and the decoder
// options that decode it. make_ssi_examples writes them; the golden test re-generates
// them and checks both the files and the decoder's output against the truth.
#include <map>
#include <string>
#include <vector>

#include "ssi_generator.h"

namespace busdecode {

struct SsiExample {
    std::string file;    // name in captures/, e.g. "ssi_tmc8100_gray25.vcd"
    std::string format;  // "vcd", "sigrok-csv", "saleae-csv"
    std::string description;
    std::map<std::string, std::string> options;  // --opt KEY=VALUE for `decode --proto ssi`
    SsiGenerated gen;
};

std::vector<SsiExample> ssiExamples();

}  // namespace busdecode
