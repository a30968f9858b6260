#pragma once
// The UART example captures shipped in captures/uart_*: how each is generated and how
// to decode it. make_uart_examples writes them; tests/uart re-generates them and checks
// that the committed files decode exactly like the in-memory truth.
#include <string>
#include <vector>

#include "core/session.h"
#include "core/waveform.h"

namespace busdecode {

struct UartExample {
    std::string file;  // name in captures/
    std::string description;
    std::vector<DecoderRequest> requests;  // what `decode FILE --proto ... --opt ...` asks for
    Waveform wave;
};

std::vector<UartExample> uartExamples();

}  // namespace busdecode
