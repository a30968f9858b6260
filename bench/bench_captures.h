#pragma once
// The benchmark buses, built with each decoder's own signal generator: one "chunk" of
// traffic whose lines end at the levels they started with, so make_capture can repeat it
// back to back into a capture of any size and the micro-benchmarks can decode it as is.
#include <cstdint>
#include <string>
#include <vector>

#include "core/session.h"
#include "core/waveform.h"

namespace busdecode::bench {

// 100 MHz sampling: one tick per sample, as a logic analyser (and dense CSV) sees it.
inline constexpr std::int64_t kSampleRateHz = 100'000'000;

struct BenchBus {
    std::string id;                        // "spi", "bissc", ...
    Waveform chunk;                        // starts at tick 0, ends at chunk.end (= its period)
    std::vector<DecoderRequest> requests;  // how `decode` is asked to decode it
    std::string decode_args;               // the same as CLI arguments (bench/run.sh)
    std::string sigrok_args;               // sigrok-cli -P ... for the same lines
};

// Names of the buses this build can generate (decoders built in).
std::vector<std::string> availableBuses();
// `units` transfers / frames / bytes of the named bus; throws std::invalid_argument.
BenchBus makeBus(const std::string& id, int units, std::uint32_t seed = 1);

// Registers the factories of every decoder built in (the CLI loads them as plugins).
void registerDecoders();

}  // namespace busdecode::bench
