#pragma once
// The example captures shipped in captures/spi_*: how each is generated and the decoder
// options that decode it. make_spi_examples writes them; tests/spi re-generates them and
// checks that the committed files decode exactly like the in-memory truth.
#include <map>
#include <string>
#include <vector>

#include "core/waveform.h"

namespace busdecode {

struct SpiExample {
    std::string file;    // name in captures/
    std::string format;  // "vcd" or "saleae-csv"
    std::string description;
    std::map<std::string, std::string> options;  // --opt KEY=VALUE for `decode --proto spi`
    Waveform wave;
};

std::vector<SpiExample> spiExamples();

}  // namespace busdecode
