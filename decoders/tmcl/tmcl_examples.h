#pragma once
// The TMCL example captures shipped in captures/tmcl_*: how each is generated and how
// to decode it. make_tmcl_examples writes them; tests/tmcl re-generates them and checks
// that the committed files decode exactly like the in-memory truth.
#include <string>
#include <vector>

#include "core/session.h"
#include "core/waveform.h"

namespace busdecode {

struct TmclExample {
    std::string file;  // name in captures/
    std::string description;
    std::vector<DecoderRequest> requests;  // what `decode FILE --proto ... --opt ...` asks for
    Waveform wave;
};

std::vector<TmclExample> tmclExamples();

}  // namespace busdecode
