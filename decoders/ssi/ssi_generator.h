#pragma once
// SSI signal generator (the Saleae idea: the test source lives beside the decoder). It
// simulates a master clocking an encoder: latch on the first falling edge, one bit per
// rising edge (MSB or LSB first), ring shift while the master keeps clocking (gap zeros,
// then the word again), data low after the word until the monoflop time tm has passed
// since the last clock edge, and a re-read of the latched word when a burst starts
// before that. Cable delay, clock jitter, glitches and truncation are knobs. Next to the
// waveform it returns the truth: what a correct decoder reports for each frame.
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/waveform.h"

namespace busdecode {

struct SsiGenFrame {
    std::uint64_t word = 0;   // the encoder's data word (without the lead bit)
    int clocks = 0;           // clock pulses; 0 = enough for `repeats` transmissions
    int repeats = 1;          // complete transmissions to clock out when clocks == 0
    double pause_ns = 50000;  // from the previous burst's last clock edge (from t=0 for the
                              // first burst) to this burst's first falling edge
    // (transmission >= 1, bit index in wire order): repeat bits sent inverted.
    std::vector<std::pair<int, int>> flips;
    // A faulty encoder: latch `word` even when the burst is a re-read (monoflop running).
    bool relatch = false;
};

struct SsiGlitch {
    int line = 0;  // 0 clock, 1 data
    double at_ns = 0;
    double width_ns = 20;
};

struct SsiGenConfig {
    int data_bits = 25;  // the encoder's word width
    bool lead = false;   // the master counts its first sample (POSITAL): raw is data_bits+1 wide
    bool lsb_first = false;
    int ring_gap = 1;  // zeros between repeated words
    double clock_hz = 1e6;
    double jitter_ns = 0;  // every clock edge moves by up to +- this (uniform)
    double tm_ns = 20000;
    double delay_ns = 0;                          // data lags the clock by this (cable round trip)
    std::int64_t sample_rate_hz = 1'000'000'000;  // the capture's timebase (one tick per sample)
    double lead_in_ns = 0;                        // idle before the first burst's pause starts
    double tail_ns = 60000;                       // idle after the last edge
    double cut_ns = -1;                           // >= 0: the capture ends here (truncation)
    std::vector<SsiGlitch> glitches;
    std::uint64_t seed = 1;
    std::string clk_name = "clk";
    std::string data_name = "data";
};

// What a correct decoder reports for one burst.
struct SsiTruth {
    Tick start = 0;  // first falling clock edge
    Tick end = 0;    // last clock edge
    std::uint64_t raw = 0;
    int bits = 0;  // bits of raw received
    bool short_frame = false;
    int repeats = 0;
    int partial_bits = 0;
    bool repeat_match = true;
    std::vector<std::int64_t> diff_bits;
    bool reread = false;
    std::optional<double> tm_ns;  // data low time after the last clock edge, if seen
    double clock_hz = 0;
};

struct SsiGenerated {
    Waveform wave;
    std::vector<SsiTruth> frames;
};

SsiGenerated generateSsi(const SsiGenConfig& cfg, const std::vector<SsiGenFrame>& frames);

}  // namespace busdecode
