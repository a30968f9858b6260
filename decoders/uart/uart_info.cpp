// The UART decoder's declaration (roles, options, events) and its registry entry.
#include <memory>

#include "core/options.h"
#include "core/registry.h"
#include "uart_decoder.h"

namespace busdecode {

std::shared_ptr<const DecoderFactory> makeUartFactory() {
    DecoderInfo info;
    info.id = "uart";
    info.name = "UART";
    info.description =
        "Asynchronous serial (RS-232/RS-485/TTL): bytes on rx and/or tx, sampled mid-bit from the "
        "start edge; framing and parity errors, breaks; baud=auto measures the shortest pulse";
    info.roles = {
        {"rx", false, {"rxd"}, "receive line (idle high unless invert=1)"},
        {"tx", false, {"txd"}, "transmit line"},
    };
    info.need_one_of = {"rx", "tx"};
    info.options = {
        numberOption("baud", "9600", 1, 1e9,
                     "bit rate in bit/s, or auto: measured from the shortest pulse", true),
        intOption("bits", "8", 5, 9, "data bits per character"),
        choiceOption("parity", {"none", "even", "odd", "mark", "space", "ignore"},
                     "parity bit (ignore: present but not checked)"),
        choiceOption("stop", {"0.5", "1", "1.5", "2"}, "stop bits", "1"),
        boolOption("invert", "0", "1: the lines idle low (inverted levels)"),
        boolOption("lsb_first", "1", "bit order of the data bits (UART sends LSB first)"),
    };
    using K = FieldSpec::Kind;
    info.events = {
        {"byte", "one character", {{"value", K::Int}, {"line", K::Text}, {"parity_ok", K::Bool}}},
        {"break",
         "the line held low for at least a whole frame",
         {{"line", K::Text}, {"duration_ns", K::Int}}},
        {"baud",
         "baud=auto: the detected rate",
         {{"baud", K::Number}, {"measured_baud", K::Number}}},
    };
    return std::make_shared<SimpleFactory<UartDecoder>>(std::move(info));
}

}  // namespace busdecode
