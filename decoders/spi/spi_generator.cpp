#include "spi_generator.h"

#include <cmath>

namespace busdecode {

SpiGenerator::SpiGenerator(WaveBuilder& wb, SpiLines lines, SpiMode mode, SpiTiming timing)
    : wb_(wb), lines_(lines), mode_(mode), timing_(timing) {}

std::vector<std::uint8_t> SpiGenerator::idleLevels(const SpiMode& mode) {
    return {std::uint8_t(mode.cs_active_high ? 0 : 1), std::uint8_t(mode.cpol), 0, 0};
}

double SpiGenerator::transfer(double t0, const std::vector<Word>& words, int bits, int cut_after) {
    const double h = timing_.period_ns / 2;
    const int total_bits = int(words.size()) * bits;
    const int n = (cut_after >= 0 && cut_after < total_bits) ? cut_after : total_bits;
    auto bitOf = [&](std::uint64_t v, int i) {
        const int pos = mode_.lsb_first ? i : bits - 1 - i;
        return pos < 64 && ((v >> pos) & 1u) != 0;
    };
    auto drive = [&](int line, double t, bool level) {
        if (line >= 0) wb_.setNs(std::uint32_t(line), t, level);
    };

    drive(lines_.cs, t0, mode_.cs_active_high);
    const double first_edge = t0 + timing_.cs_setup_ns;
    const bool idle = mode_.cpol != 0;
    for (int k = 0; k < n; ++k) {
        const Word& w = words[std::size_t(k / bits)];
        const int i = k % bits;
        const double lead = first_edge + k * timing_.period_ns;
        const double trail = lead + h;
        // CPHA=0: data is out before the leading (sampling) edge, shifted on the trailing
        // one; CPHA=1: shifted on the leading edge, sampled on the trailing one.
        double data_t;
        if (mode_.cpha == 0)
            data_t = (k == 0 ? t0 : trail - timing_.period_ns) + timing_.data_delay_ns;
        else
            data_t = lead + timing_.data_delay_ns;
        drive(lines_.mosi, data_t, bitOf(w.mosi, i));
        drive(lines_.miso, data_t, bitOf(w.miso, i));
        drive(lines_.sclk, lead, !idle);
        drive(lines_.sclk, trail, idle);
    }
    const double last = n > 0 ? first_edge + (n - 1) * timing_.period_ns + h : first_edge;
    const double release = last + timing_.cs_hold_ns;
    drive(lines_.cs, release, !mode_.cs_active_high);
    return release;
}

Waveform makeSpiCapture(const std::vector<std::vector<SpiGenerator::Word>>& transfers, int bits,
                        SpiMode mode, SpiTiming timing, double gap_ns) {
    WaveBuilder wb(Timebase{1, 1'000'000'000}, {"cs", "sclk", "mosi", "miso"},
                   SpiGenerator::idleLevels(mode));
    SpiGenerator gen(wb, SpiLines{0, 1, 2, 3}, mode, timing);
    double t = gap_ns;
    for (const auto& words : transfers)
        t = gen.transfer(t, words, bits) + gap_ns;
    return wb.build(wb.ticksFromNs(t));
}

}  // namespace busdecode
