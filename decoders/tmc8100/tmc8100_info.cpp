#include "core/registry.h"
#include "spi_info.h"
#include "tmc8100_decoder.h"

namespace busdecode {

DecoderInfo tmc8100Info() {
    DecoderInfo info;
    info.id = "tmc8100";
    info.name = "TMC8100 SPI";
    info.description =
        "Trinamic/ADI TMC8100 encoder interface: 32-bit SPI datagrams of the example firmwares "
        "(read encoder, version, protocol) and of the bootloader, replies paired with their "
        "commands, cross-checked against an ssi or bissc decoder in the same pass";
    info.roles = spiRoleSpecs();
    info.roles.push_back(
        {"avail",
         false,
         {"gpio6", "spi_data_available"},
         "SPI_DATA_AVAILABLE (GPIO6): high while replies wait in the output buffer"});
    info.options = spiOptionSpecs();  // passed through to the SPI layer, same defaults
    info.options.push_back(
        choiceOption("mode", {"auto", "app", "bootloader"},
                     "program on the chip: application firmware, bootloader, or detect "
                     "(chip id/revision queries or consecutive program writes mean bootloader)"));
    info.options.push_back(
        choiceOption("encoder", {"auto", "ssi", "biss"},
                     "encoder protocol of the firmware (auto: from the get_protocol reply, or "
                     "a 0x71 word after the flags)"));
    using K = FieldSpec::Kind;
    // A reply's fields after `word` depend on the command it answers.
    info.events = {
        {"command",
         "a host datagram on MOSI",
         {{"code", K::Int},
          {"name", K::Text},
          {"word", K::Int},
          {"address", K::Int},
          {"data", K::Int}}},
        {"reply",
         "a reply word on MISO paired with its command",
         {{"tag", K::Int},     {"value", K::Int},       {"meaning", K::Text}, {"command", K::Text},
          {"address", K::Int}, {"word", K::Int},        {"position", K::Int}, {"nE", K::Int},
          {"nW", K::Int},      {"crc_rx", K::Int},      {"crc_calc", K::Int}, {"crc_ok", K::Bool},
          {"flags", K::Int},   {"clock_edges", K::Int}, {"major", K::Int},    {"minor", K::Int},
          {"text", K::Text},   {"version", K::Int},     {"revision", K::Int}, {"data", K::Int}}},
        {"encoder_read",
         "one complete 0x80 read",
         {{"gray", K::Int},
          {"binary", K::Int},
          {"flags", K::Int},
          {"consistent", K::Bool},
          {"nE", K::Int},
          {"nW", K::Int},
          {"crc_rx", K::Int},
          {"crc_calc", K::Int},
          {"crc_ok", K::Bool},
          {"clock_edges", K::Int},
          {"ssi_match", K::Bool},
          {"encoder_st", K::Int}}},
        {"avail", "GPIO6 behaviour that contradicts the traffic", {{"level", K::Int}}},
    };
    info.need_one_of = {"mosi", "miso"};
    return info;
}

std::shared_ptr<const DecoderFactory> makeTmc8100Factory() {
    // The SPI layer is linked in.
    return std::make_shared<StackedFactory<Tmc8100Decoder>>(
        tmc8100Info(), std::vector<std::shared_ptr<const DecoderFactory>>{makeSpiFactory()});
}

}  // namespace busdecode
