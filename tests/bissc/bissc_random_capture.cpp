#include "bissc_random_capture.h"

#include <random>

#include "bissc_generator.h"

namespace busdecode::test {

// A capture of `frames` frames with everything the generator can vary drawn at random:
// the sample rate, line delays of up to several bit times, jitter, busy clocks, clocks
// past the stop bit, a slave that takes those for a new request, Hold-CDM, corrupted
// CRCs, frames cut short, and glitches on both lines.
Waveform randomCapture(std::uint32_t seed, int frames) {
    std::mt19937_64 rng(seed);
    const auto pick = [&rng](int n) { return int(rng() % std::uint64_t(n)); };
    BisscGenConfig cfg;
    const double clocks[] = {1e6, 2.5e6, 10e6};
    cfg.clock_hz = clocks[pick(3)];
    const double period_ns = 1e9 / cfg.clock_hz;
    cfg.bits = 26;
    cfg.line_delay_ns = period_ns * 0.1 * pick(40);  // 0 to 3.9 bit times
    const std::int64_t rates[] = {0, 24'000'000, 100'000'000};
    if (const std::int64_t rate = rates[pick(3)]) {
        cfg.timebase = Timebase::fromSampleRate(rate);
    } else {
        cfg.jitter_ns = period_ns * 0.01 * pick(6);  // 0 to 5 % of a period
    }
    cfg.hold_cdm = pick(4) == 0;
    if (pick(4) == 0) cfg.ready_after_stop_ns = period_ns * pick(3);
    cfg.timeout_ns = 15000 + 2 * period_ns;
    cfg.seed = seed;
    BisscGenerator gen(cfg);
    for (int i = 0; i < frames; ++i) {
        BisscFrameSpec f;
        f.data = rng() & ((1ull << 26) - 1);
        f.ne = int(pick(5) != 0);
        f.nw = int(pick(4) != 0);
        f.cds = pick(2);
        f.cdm = pick(2);
        f.proc_cycles = pick(6);
        f.extra_clocks = pick(3) == 0 ? pick(5) : 0;
        f.corrupt_crc = pick(7) == 0;
        if (pick(9) == 0) f.truncate_after = 2 + pick(38);
        const double start = gen.nowNs();
        gen.addFrame(f);
        if (pick(6) == 0)
            gen.addGlitch(pick(2), start + (gen.nowNs() - start) * 0.01 * pick(100), 5);
    }
    return gen.build();
}

}  // namespace busdecode::test
