// The tokenisers: VCD, CSV and sigrok session files (written with the project's writers
// into a temporary directory) read through openCapture, edges counted and dropped.
// Measures bytes per second of the reader alone (of the file; for a session, of its
// compressed file, with samples/s beside), with all lines mapped and with only one.
#include <benchmark/benchmark.h>

#include <filesystem>
#include <map>

#include "bench_captures.h"
#include "capture/capture_writer.h"
#include "core/scratch_dir.h"
#include "read_edges.h"

namespace busdecode::bench {
namespace {

namespace fs = std::filesystem;

// The traffic every file holds (about 20 MB of SPI as VCD).
const BenchBus& benchBus() {
    static const BenchBus bus = makeBus("spi", 20000);
    return bus;
}

// One file per format, written once per process.
const std::string& benchFile(const std::string& format) {
    static const ScratchDir dir("busdecode-bench");
    static std::map<std::string, std::string> files;
    auto it = files.find(format);
    if (it != files.end()) return it->second;
    const BenchBus& bus = benchBus();
    std::string path = (fs::path(dir.path()) / ("spi." + format)).string();
    if (format == "vcd") {
        writeVcd(bus.chunk, path);
    } else if (format == "vcd_late") {
        // The same traffic 10 s into a capture: 10-digit timestamps, as in every capture
        // longer than that at 100 MS/s and in bench/run.sh's 500 MB files (the digits
        // past the eighth take the tokeniser's second round).
        constexpr Tick kLate = 1'000'000'000;
        Waveform late = bus.chunk;
        for (Edge& e : late.edges)
            e.t += kLate;
        late.start += kLate;
        late.end += kLate;
        writeVcd(late, path);
    } else if (format == "csv_saleae") {
        // Saleae Logic 2's export: one row per change, times as decimal seconds.
        path = (fs::path(dir.path()) / "spi_saleae.csv").string();
        writeCsv(bus.chunk, path, CsvDialect::SaleaeLogic2);
    } else if (format == "sr") {
        writeSr(bus.chunk, path);  // a sigrok session: deflated samples, one byte each
    } else {
        writeCsv(bus.chunk, path, CsvDialect::SigrokDense);
    }
    return files.emplace(format, path).first->second;
}

void readFile(benchmark::State& state, const std::string& format, bool all_lines) {
    const std::string& path = benchFile(format);
    std::uint64_t bytes = 0, edges = 0;
    for (auto _ : state) {
        // All lines, or sclk only: the other columns must be skipped cheaply.
        edges += readEdges(path, all_lines ? -1 : 1);
        bytes += fs::file_size(path);
    }
    state.SetBytesProcessed(std::int64_t(bytes));
    state.counters["edges/s"] = benchmark::Counter(double(edges), benchmark::Counter::kIsRate);
    // Samples of capture read per second, whatever the format stores (the same traffic).
    const Waveform& w = benchBus().chunk;
    state.counters["samples/s"] = benchmark::Counter(
        double(w.end - w.start + 1) * double(state.iterations()), benchmark::Counter::kIsRate);
}

BENCHMARK_CAPTURE(readFile, vcd_all_lines, std::string("vcd"), true)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(readFile, vcd_one_line, std::string("vcd"), false)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(readFile, vcd_late_all_lines, std::string("vcd_late"), true)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(readFile, csv_all_lines, std::string("csv"), true)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(readFile, csv_one_line, std::string("csv"), false)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(readFile, csv_saleae_all_lines, std::string("csv_saleae"), true)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(readFile, csv_saleae_one_line, std::string("csv_saleae"), false)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(readFile, sr_all_lines, std::string("sr"), true)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(readFile, sr_one_line, std::string("sr"), false)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace busdecode::bench
