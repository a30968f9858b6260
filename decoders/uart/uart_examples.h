#pragma once
// The example captures shipped in captures/uart_*, in the kit's shape (decoders/kit):
// make_examples writes them; tests/uart re-generates them and checks that the committed
// files decode exactly like the in-memory waveform.
#include <vector>

#include "example.h"

namespace busdecode {

using UartExample = Example<>;

std::vector<UartExample> uartExamples();

}  // namespace busdecode
