#include "spi_info.h"

#include "core/registry.h"
#include "spi_decoder.h"

namespace busdecode {

std::vector<RoleSpec> spiRoleSpecs() {
    return {
        {"cs",
         false,
         {"csn", "ss", "nss", "spi_csn"},
         "chip select (optional; active low unless cs_polarity)"},
        {"sclk", true, {"sck", "clk", "spi_sclk"}, "serial clock from the host"},
        {"mosi", false, {"sdi", "spi_sdi"}, "host to device data"},
        {"miso", false, {"sdo", "spi_sdo"}, "device to host data"},
    };
}

std::vector<OptionSpec> spiOptionSpecs() {
    return {
        intOption("cpol", "1", 0, 1, "clock level when idle (0 or 1)"),
        intOption("cpha", "1", 0, 1,
                  "0: sample on the leading clock edge, 1: sample on the trailing edge"),
        intOption("bits", "32", 1, 64, "bits per word"),
        boolOption("lsb_first", "0", "0: MSB first, 1: LSB first"),
        choiceOption("cs_polarity", {"active-low", "active-high"},
                     "level of cs while a transfer is selected"),
    };
}

DecoderInfo spiInfo() {
    DecoderInfo info;
    info.id = "spi";
    info.name = "SPI";
    info.description =
        "Serial Peripheral Interface: words of 1..64 bits on MOSI/MISO, any CPOL/CPHA, MSB or "
        "LSB first, framed by chip select or (without cs) by bit count only";
    info.roles = spiRoleSpecs();
    info.options = spiOptionSpecs();
    using K = FieldSpec::Kind;
    info.events = {{"transfer",
                    "one word: mosi and miso (null for an unbound line), bits; a word cut short "
                    "by cs or by the end of the capture has the error short_frame",
                    {{"mosi", K::Int}, {"miso", K::Int}, {"bits", K::Int}}}};
    info.need_one_of = {"mosi", "miso"};
    return info;
}

std::shared_ptr<const DecoderFactory> makeSpiFactory() {
    return std::make_shared<SimpleFactory<SpiDecoder>>(spiInfo());
}

}  // namespace busdecode
