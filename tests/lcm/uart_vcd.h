#pragma once
// A hand-written UART capture for the live-input tests: a VCD as a logic analyser would
// stream it, split in two so a test can hold back the second part.
#include <cstddef>
#include <string>

namespace busdecode::test {

struct UartVcd {
    std::string head, tail;
};

// `text` on one line "tx" (8N1, 10000 baud, 1 us timescale), one byte every 1.5 ms; the
// text is split after byte `split_after`, with a timestamp that moves time past that
// byte's stop bit so a decoder can finish it before more input arrives.
UartVcd uartVcd(const std::string& text, std::size_t split_after);

}  // namespace busdecode::test
