#pragma once
// Signal generator for SPI (the Saleae SimulationDataGenerator idea): drives cs, sclk,
// mosi and miso on a WaveBuilder for any CPOL/CPHA, word width and bit order, so the
// decoder's tests have signals with known truth. Also used by stacked generators
// (TMC8100) to play the host side of a scenario.
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "core/waveform.h"

namespace busdecode {

struct SpiMode {
    int cpol = 1;
    int cpha = 1;
    bool lsb_first = false;
    bool cs_active_high = false;
};

struct SpiTiming {
    double period_ns = 400;     // clock period
    double cs_setup_ns = 200;   // cs asserted -> first clock edge
    double cs_hold_ns = 200;    // last clock edge -> cs released
    double data_delay_ns = 30;  // data lines change this long after a shift edge
};

// Line indices in the WaveBuilder; -1 leaves a line out.
struct SpiLines {
    int cs = -1, sclk = -1, mosi = -1, miso = -1;
};

class SpiGenerator {
public:
    SpiGenerator(WaveBuilder& wb, SpiLines lines, SpiMode mode = {}, SpiTiming timing = {});

    struct Word {
        std::uint64_t mosi = 0, miso = 0;
    };
    // Asserts cs at t_ns, clocks the words (each `bits` wide) back to back and releases
    // cs. With cut_after >= 0 the transfer stops after that many bits in total (a word
    // cut short by cs). Returns the time cs was released (ns).
    double transfer(double t_ns, const std::vector<Word>& words, int bits, int cut_after = -1);
    double transfer(double t_ns, std::uint64_t mosi, std::uint64_t miso, int bits) {
        return transfer(t_ns, std::vector<Word>{{mosi, miso}}, bits);
    }

    const SpiMode& mode() const { return mode_; }
    const SpiTiming& timing() const { return timing_; }

    // Initial levels for the four lines of a bus built only for SPI (cs inactive,
    // clock at cpol, data low).
    static std::vector<std::uint8_t> idleLevels(const SpiMode& mode);

private:
    WaveBuilder& wb_;
    SpiLines lines_;
    SpiMode mode_;
    SpiTiming timing_;
};

// A whole SPI capture in 1 ns ticks with lines cs, sclk, mosi, miso: one transfer per
// entry of `transfers`, `gap_ns` apart.
Waveform makeSpiCapture(const std::vector<std::vector<SpiGenerator::Word>>& transfers, int bits,
                        SpiMode mode = {}, SpiTiming timing = {}, double gap_ns = 1000);

}  // namespace busdecode
