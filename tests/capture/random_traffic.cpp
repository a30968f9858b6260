#include "random_traffic.h"

#include <random>

namespace busdecode::test {

Waveform randomTraffic(Timebase tb, std::uint32_t seed, int changes, int max_gap, Tick first,
                       Tick tail) {
    std::mt19937 rng(seed);
    WaveBuilder b(tb, {"clk", "data", "cs"}, {1, 0, 1});
    Tick t = first;
    for (int i = 0; i < changes; ++i) {
        t += 1 + Tick(rng() % std::uint32_t(max_gap));
        const auto l = std::uint32_t(rng() % 3);
        b.set(l, t, !b.level(l));
    }
    return b.build(t + tail);
}

}  // namespace busdecode::test
