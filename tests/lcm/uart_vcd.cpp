#include "uart_vcd.h"

namespace busdecode::test {

UartVcd uartVcd(const std::string& text, std::size_t split_after) {
    const int bit_us = 100;
    std::string out =
        "$timescale 1us $end\n$scope module top $end\n$var wire 1 ! tx $end\n"
        "$upscope $end\n$enddefinitions $end\n#0\n1!\n";
    UartVcd v;
    long t = 1000;
    for (std::size_t i = 0; i < text.size(); ++i) {
        unsigned char c = static_cast<unsigned char>(text[i]);
        int level = 1;
        for (int k = 0; k < 10; ++k) {
            int bit = k == 0 ? 0 : k == 9 ? 1 : (c >> (k - 1)) & 1;
            if (bit != level)
                out += "#" + std::to_string(t + k * bit_us) + " " + std::to_string(bit) + "!\n";
            level = bit;
        }
        t += 10 * bit_us + 500;
        if (i + 1 == split_after) {
            out += "#" + std::to_string(t - 400) + "\n";
            v.head = out;
            out.clear();
        }
    }
    out += "#" + std::to_string(t) + "\n";
    v.tail = out;
    return v;
}

}  // namespace busdecode::test
