#pragma once
// The example captures shipped in captures/tmc8100_*: how each is generated and how to
// decode it. make_tmc8100_examples writes them; tests/tmc8100 re-generates them and
// checks that the committed files decode exactly like the in-memory truth.
#include <string>
#include <vector>

#include "core/session.h"
#include "core/waveform.h"

namespace busdecode {

struct Tmc8100Example {
    std::string file;  // name in captures/
    std::string description;
    std::vector<DecoderRequest> requests;  // what `decode FILE --proto ... --opt ...` asks for
    Waveform wave;
};

std::vector<Tmc8100Example> tmc8100Examples();

// The decode command line for an example (for the maker and the README).
std::string decodeCommand(const std::string& file, const std::vector<DecoderRequest>& requests);

}  // namespace busdecode
