// The TMCL decoder's declaration (roles, options, events) and its registry entry, stacked
// on the UART decoder.
#include <memory>

#include "core/options.h"
#include "core/registry.h"
#include "tmcl_decoder.h"
#include "uart_decoder.h"

namespace busdecode {

std::shared_ptr<const DecoderFactory> makeTmclFactory() {
    DecoderInfo info;
    info.id = "tmcl";
    info.name = "TMCL";
    info.description =
        "Trinamic TMCL datagrams over UART/RS-485 (stacked on uart): commands in TMCL-IDE "
        "mnemonics with TMCM-1690 parameter names, replies with status text, pairing and "
        "round-trip time, checksum faults";
    info.roles = {
        {"host", false, {"tx", "txd"}, "host to module line"},
        {"module", false, {"rx", "rxd"}, "module to host line"},
        {"bus", false, {"rs485", "line"}, "one half-duplex RS-485 line carrying both directions"},
    };
    info.need_one_of = {"host", "module", "bus"};
    info.options = {
        numberOption("baud", "9600", 1, 1e9,
                     "bit rate passed to the UART layer, or auto (shortest pulse)", true),
        intOption("host_address", "auto", 0, 255,
                  "host (reply) address; helps tell replies from commands on a bus line", true),
        intOption("module_address", "auto", 0, 255,
                  "module address; helps tell commands from replies on a bus line", true),
        numberOption("gap_bytes", "3", 0.5, 1e6,
                     "a pause longer than this many character times inside a datagram "
                     "resynchronises"),
        boolOption("invert", "0", "1: the lines idle low"),
    };
    using K = FieldSpec::Kind;
    // A datagram cut short has its bytes and length besides the fields it reached.
    info.events = {
        {"command",
         "host to module datagram",
         {{"address", K::Int},
          {"command", K::Int},
          {"mnemonic", K::Text},
          {"type_no", K::Int},
          {"motor", K::Int},
          {"value", K::Int},
          {"checksum_ok", K::Bool},
          {"checksum", K::Int},
          {"parameter", K::Text},
          {"text", K::Text},
          {"bytes", K::IntList},
          {"length", K::Int}}},
        {"reply",
         "module to host datagram (paired with its command)",
         {{"reply_address", K::Int},
          {"module_address", K::Int},
          {"status", K::Int},
          {"status_text", K::Text},
          {"command", K::Int},
          {"value", K::Int},
          {"checksum_ok", K::Bool},
          {"checksum", K::Int},
          {"mnemonic", K::Text},
          {"version", K::Text},
          {"request", K::Text},
          {"request_start_ns", K::Int},
          {"rtt_ns", K::Int},
          {"latency_ns", K::Int},
          {"bytes", K::IntList},
          {"length", K::Int}}},
    };
    // The UART layer is linked in.
    return std::make_shared<StackedFactory<TmclDecoder>>(
        std::move(info), std::vector<std::shared_ptr<const DecoderFactory>>{makeUartFactory()});
}

}  // namespace busdecode
