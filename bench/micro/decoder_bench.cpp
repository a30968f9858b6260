// Each decoder's cost per edge: a Session over an in-memory capture (no file, no
// tokenising), the events counted and dropped, so only binding, merging, decoding and
// event release are measured.
#include <benchmark/benchmark.h>

#include "bench_captures.h"
#include "capture/capture_reader.h"
#include "sinks/counting_sink.h"

namespace busdecode::bench {
namespace {

void decodeBus(benchmark::State& state, const std::string& id, int units) {
    registerDecoders();
    const BenchBus bus = makeBus(id, units);
    std::uint64_t edges = 0, events = 0;
    for (auto _ : state) {
        auto reader = memoryReader(bus.chunk);
        Session session(bus.requests, *reader, "memory");
        CountingSink sink;
        session.addSink(&sink);
        session.run();
        edges += session.facts().edges;
        events += sink.events();
    }
    state.SetItemsProcessed(std::int64_t(edges));
    state.counters["ns/edge"] = benchmark::Counter(
        double(edges), benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
    state.counters["edges"] = double(edges) / double(state.iterations());
    state.counters["events"] = double(events) / double(state.iterations());
    // Capture seconds decoded per wall second: > 1 means faster than the bus runs.
    const double capture_s =
        double(bus.chunk.end - bus.chunk.start) * bus.chunk.timebase.secondsPerTick();
    state.counters["x_realtime"] =
        benchmark::Counter(capture_s * double(state.iterations()), benchmark::Counter::kIsRate);
}

// Registers one benchmark per bus built into this binary.
const int kRegistered = [] {
    for (const auto& id : availableBuses()) {
        // Enough traffic for a million edges or so per run.
        const int units = id == "uart"                ? 20000
                          : id.rfind("bissc", 0) == 0 ? 20000
                          : id == "tmcl"              ? 500
                          : id == "tmc8100"           ? 200
                                                      : 2000;
        benchmark::RegisterBenchmark(("decode/" + id).c_str(), [id, units](benchmark::State& s) {
            decodeBus(s, id, units);
        })->Unit(benchmark::kMillisecond);
    }
    return 0;
}();

}  // namespace
}  // namespace busdecode::bench
