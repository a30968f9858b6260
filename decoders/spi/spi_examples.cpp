#include "spi_examples.h"

#include "spi_generator.h"

namespace busdecode {

namespace {

SpiExample mode0Lsb16() {
    // Mode 0, LSB first, two 16-bit words per chip select, and a transfer the host cuts
    // short after 11 bits (reported with short_frame).
    SpiMode mode{0, 0, true, false};
    SpiTiming tm{1000, 500, 500, 50};
    WaveBuilder wb(Timebase{1, 1'000'000'000}, {"cs", "sclk", "mosi", "miso"},
                   SpiGenerator::idleLevels(mode));
    SpiGenerator gen(wb, {0, 1, 2, 3}, mode, tm);
    double t = gen.transfer(2000, {{0x1234, 0xFFFF}, {0xABCD, 0x0001}}, 16) + 3000;
    t = gen.transfer(t, {{0x8001, 0x7FFE}, {0x0F0F, 0xF0F0}}, 16) + 3000;
    t = gen.transfer(t, {{0x5555, 0xAAAA}}, 16, 11) + 3000;
    t = gen.transfer(t, {{0xC3C3, 0x3C3C}}, 16) + 3000;
    return {
        {"spi_mode0_lsb16.vcd",
         ExampleFormat::Vcd,
         "SPI mode 0, LSB first, 16-bit words (two per cs), one transfer cut short after 11 bits",
         {{"spi", {}, {{"cpol", "0"}, {"cpha", "0"}, {"bits", "16"}, {"lsb_first", "1"}}}},
         wb.build(wb.ticksFromNs(t))}};
}

SpiExample mode3Datagrams() {
    // The contract defaults (mode 3, MSB first, 32 bits): TMC8100-style datagrams at
    // 2.66 MHz, exported the way Saleae Logic 2 writes CSV (one row per change).
    SpiTiming tm{376, 500, 500, 30};
    std::vector<std::vector<SpiGenerator::Word>> transfers = {{{0xFE000000, 0}}, {{0, 0x53534920}},
                                                              {{0x80000000, 0}}, {{0, 0x10001B2E}},
                                                              {{0, 0x20001234}}, {{0, 0x70000000}}};
    return {{"spi_mode3_32bit_saleae.csv",
             ExampleFormat::SaleaeCsv,
             "SPI mode 3, 32-bit datagrams (the contract defaults), Saleae Logic 2 CSV export",
             {{"spi", {}, {}}},
             makeSpiCapture(transfers, 32, SpiMode{}, tm, 4000)}};
}

}  // namespace

std::vector<SpiExample> spiExamples() {
    return {mode0Lsb16(), mode3Datagrams()};
}

// make_examples finds them here (this library is linked whole: CMake OBJECT library).
[[maybe_unused]] const bool kListed = listExamples("spi", spiExamples);

}  // namespace busdecode
