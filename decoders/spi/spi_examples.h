#pragma once
// The example captures shipped in captures/spi_*, in the kit's shape (decoders/kit):
// make_examples writes them; tests/spi re-generates them and checks that the committed
// files decode exactly like the in-memory waveform.
#include <vector>

#include "example.h"

namespace busdecode {

using SpiExample = Example<>;

std::vector<SpiExample> spiExamples();

}  // namespace busdecode
