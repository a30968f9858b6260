// make_capture: writes the large captures bench/run.sh times.
//
//   make_capture BUS FORMAT SIZE_MB OUT [FIRST_TICK]   (FORMAT: vcd, csv, saleae or sr)
//
// FIRST_TICK (VCD only): the repeated traffic starts at the first chunk period at or after
// this tick, after a quiet stretch, as in the later part of a long capture: times of 9
// digits from 100000000 (1 s at 100 MS/s), 10 from 1000000000. The profile-guided build
// trains on such files (cmake/pgo_train.sh), whose small captures would otherwise only
// have short times.
//
// sr (a sigrok session) is SIZE_MB of samples before compression: one byte a sample up
// to eight lines, 1e6 samples per MB.
//
// BUS: spi, bissc, uart, ... (bench_captures.cpp); spi-periodic and bissc-periodic are the
// same traffic with the same data in every word or frame (what unpredictable data costs).
//
// One chunk of traffic is made with the decoder's own generator and written with the
// project's writers (writeVcd, writeCsv: sigrok dense or Saleae CSV) into a temporary file; the
// chunk ends at the levels it started with, so its body is then repeated, VCD timestamps
// shifted by one chunk period each time, until the file reaches SIZE_MB. The result is
// what the writer would produce for the whole long capture, without holding it in memory.
#include <algorithm>
#include <cinttypes>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "bench_captures.h"
#include "capture/capture_writer.h"
#include "capture/decimal_scan.h"

namespace {

using namespace busdecode;

std::string slurp(const std::string& path) {
    std::ifstream f(path, std::ios::binary);
    std::ostringstream ss;
    ss << f.rdbuf();
    return ss.str();
}

std::vector<std::string_view> splitLines(std::string_view text) {
    std::vector<std::string_view> lines;
    while (!text.empty()) {
        auto nl = text.find('\n');
        if (nl == std::string_view::npos) nl = text.size() - 1;
        lines.push_back(text.substr(0, nl + 1));
        text.remove_prefix(nl + 1);
    }
    return lines;
}

// A timestamp line "#123 ..." -> 123; other lines -> -1.
std::int64_t timestampOf(std::string_view line) {
    if (line.empty() || line[0] != '#') return -1;
    return std::strtoll(std::string(line.substr(1, 24)).c_str(), nullptr, 10);
}

class Output {
public:
    explicit Output(const std::string& path) : f_(std::fopen(path.c_str(), "wb")) {
        if (!f_) throw std::runtime_error("cannot write " + path);
        std::setvbuf(f_, nullptr, _IOFBF, 1 << 20);
    }
    ~Output() {
        if (f_) std::fclose(f_);
    }
    void put(std::string_view s) {
        std::fwrite(s.data(), 1, s.size(), f_);
        bytes_ += s.size();
    }
    std::uint64_t bytes() const { return bytes_; }

private:
    std::FILE* f_;
    std::uint64_t bytes_ = 0;
};

void repeatVcd(const std::string& chunk_file, const Waveform& chunk, std::uint64_t target,
               std::int64_t first_tick, Output& out) {
    const std::string text = slurp(chunk_file);
    const auto lines = splitLines(text);
    // Header: everything up to the line with $enddefinitions; then the initial dump (all
    // lines before the first timestamp after the chunk start); then the edges.
    std::size_t body = 0;
    while (body < lines.size() && lines[body].find("$enddefinitions") == std::string_view::npos)
        ++body;
    if (body == lines.size()) throw std::runtime_error("writeVcd output has no $enddefinitions");
    ++body;
    std::size_t edges = body;
    while (edges < lines.size() && timestampOf(lines[edges]) <= chunk.start)
        ++edges;
    for (std::size_t i = 0; i < edges; ++i)
        out.put(lines[i]);

    const std::int64_t period = chunk.end - chunk.start;
    std::uint64_t body_bytes = 0;
    for (std::size_t i = edges; i < lines.size(); ++i)
        body_bytes += lines[i].size();
    char stamp[32];
    // The levels hold from the initial dump until the first repetition's first time.
    const std::int64_t k0 = first_tick > 0 ? (first_tick + period - 1) / period : 0;
    for (std::int64_t k = k0;; ++k) {
        const bool last = out.bytes() + body_bytes >= target;
        for (std::size_t i = edges; i < lines.size(); ++i) {
            std::string_view line = lines[i];
            const std::int64_t t = timestampOf(line);
            if (t < 0) {
                out.put(line);
                continue;
            }
            const auto digits = line.find_first_not_of("0123456789", 1);
            std::string_view rest = line.substr(digits);
            // The chunk's closing timestamp (no values after it) only ends the file.
            if (!last && t >= chunk.end && (rest == "\n" || rest == "\r\n")) continue;
            std::snprintf(stamp, sizeof stamp, "#%" PRId64, t + k * period);
            out.put(stamp);
            out.put(rest);
        }
        if (last) break;
    }
}

void repeatCsv(const std::string& chunk_file, std::uint64_t target, Output& out) {
    const std::string text = slurp(chunk_file);
    // Header: comment lines and the row of column names; every later line is a sample.
    std::size_t pos = 0;
    while (pos < text.size()) {
        const char c = text[pos];
        if (c >= '0' && c <= '9') break;
        auto nl = text.find('\n', pos);
        pos = nl == std::string::npos ? text.size() : nl + 1;
    }
    out.put(std::string_view(text).substr(0, pos));
    const std::string_view body = std::string_view(text).substr(pos);
    // The writer includes the sample at the chunk's end, which is the next chunk's first:
    // every repetition but the last leaves it out.
    std::string_view joined = body;
    if (joined.size() > 1) {
        const auto nl = joined.rfind('\n', joined.size() - 2);
        if (nl != std::string_view::npos) joined = joined.substr(0, nl + 1);
    }
    while (out.bytes() + body.size() < target)
        out.put(joined);
    out.put(body);
}

// Saleae Logic 2 CSV: a row per change, times in decimal seconds with a fixed number of
// decimals (writeCsv's choice for the timebase). Each repetition shifts the times by the
// chunk's length; as in repeatCsv, the chunk's closing row (the next one's first time)
// is written only at the end.
void repeatSaleae(const std::string& chunk_file, std::uint64_t target, Output& out) {
    const std::string text = slurp(chunk_file);
    auto lines = splitLines(text);
    if (lines.size() < 3) throw std::runtime_error("writeCsv output has no rows");
    out.put(lines[0]);  // the header
    // "W.FFFFFFFFF,..." -> W * 10^decimals + F, and the rest of the row.
    struct Row {
        std::int64_t units;
        std::string_view rest;
    };
    std::vector<Row> rows;
    int decimals = -1;
    std::int64_t scale = 1;  // 10^decimals
    for (std::size_t i = 1; i < lines.size(); ++i) {
        const std::string_view l = lines[i];
        const auto dot = l.find('.'), comma = l.find(',');
        if (dot == std::string_view::npos || comma == std::string_view::npos || dot > comma)
            throw std::runtime_error("unexpected Saleae row: " + std::string(l));
        const int d = int(comma - dot - 1);
        if (decimals < 0) {
            if (d > 18) throw std::runtime_error("more than 18 decimals");
            decimals = d;
            scale = std::int64_t(kPow10[d]);
        } else if (d != decimals) {
            throw std::runtime_error("decimals vary");
        }
        rows.push_back(
            {std::strtoll(std::string(l.substr(0, dot)).c_str(), nullptr, 10) * scale +
                 std::strtoll(std::string(l.substr(dot + 1, std::size_t(d))).c_str(), nullptr, 10),
             l.substr(comma)});
    }
    const std::int64_t period = rows.back().units - rows.front().units;
    if (rows.front().units < 0) throw std::runtime_error("negative times are not repeated");
    std::uint64_t body_bytes = text.size() - lines[0].size();
    char stamp[48];
    for (std::int64_t k = 0;; ++k) {
        const bool last = out.bytes() + body_bytes >= target;
        const std::size_t n = last ? rows.size() : rows.size() - 1;
        for (std::size_t i = 0; i < n; ++i) {
            const std::int64_t u = rows[i].units + k * period;
            std::snprintf(stamp, sizeof stamp, "%" PRId64 ".%0*" PRId64, u / scale, decimals,
                          u % scale);
            out.put(stamp);
            out.put(rows[i].rest);
        }
        if (last) break;
    }
}

// A sigrok session of `target` bytes of samples (before compression): the chunk's
// samples over one period, repeated. The chunk ends at the levels it started with, so
// the sample at tick start + period is the one at start again.
std::uint64_t repeatSr(const Waveform& chunk, std::uint64_t target, const std::string& path) {
    SampleRenderer renderer(chunk);
    const std::size_t unit = renderer.unit();
    const auto period = std::size_t(chunk.end - chunk.start);
    std::vector<std::uint8_t> one(period * unit);
    renderer.render(0, period, one.data());
    const std::uint64_t samples = target / unit;
    writeSrSamples(path, chunk.names, chunk.timebase.den / chunk.timebase.num, samples,
                   [&](std::uint64_t first, std::size_t n, std::uint8_t* out) {
                       for (std::size_t done = 0; done < n;) {
                           const std::size_t at = std::size_t((first + done) % period);
                           const std::size_t run = std::min(n - done, period - at);
                           std::memcpy(out + done * unit, one.data() + at * unit, run * unit);
                           done += run;
                       }
                   });
    return std::filesystem::file_size(path);
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 5 && argc != 6) {
        std::fprintf(stderr,
                     "usage: make_capture BUS vcd|csv|saleae|sr SIZE_MB OUT [FIRST_TICK]\n");
        return 2;
    }
    try {
        const std::string bus_id = argv[1], format = argv[2], out_path = argv[4];
        std::int64_t first_tick = 0;
        if (argc == 6) {
            char* end = nullptr;
            first_tick = std::strtoll(argv[5], &end, 10);
            if (*argv[5] == '\0' || *end != '\0' || first_tick < 0 || first_tick > (1LL << 52))
                throw std::invalid_argument("FIRST_TICK must be a tick from 0 to 2^52");
            if (format != "vcd") throw std::invalid_argument("FIRST_TICK is for vcd only");
        }
        const std::uint64_t target = std::uint64_t(std::atof(argv[3]) * 1e6);
        // About 20 ms of traffic per chunk: a few MB, repeated as often as needed.
        const int units = bus_id.rfind("spi", 0) == 0     ? 800
                          : bus_id.rfind("bissc", 0) == 0 ? 3000
                                                          : 2000;
        const bench::BenchBus bus = bench::makeBus(bus_id, units);
        std::uint64_t bytes = 0;
        if (format == "sr") {
            bytes = repeatSr(bus.chunk, target, out_path);
        } else {
            const std::string chunk_file = out_path + ".chunk";
            Output out(out_path);
            if (format == "vcd") {
                writeVcd(bus.chunk, chunk_file);
                repeatVcd(chunk_file, bus.chunk, target, first_tick, out);
            } else if (format == "csv") {
                writeCsv(bus.chunk, chunk_file, CsvDialect::SigrokDense);
                repeatCsv(chunk_file, target, out);
            } else if (format == "saleae") {
                writeCsv(bus.chunk, chunk_file, CsvDialect::SaleaeLogic2);
                repeatSaleae(chunk_file, target, out);
            } else {
                throw std::invalid_argument("format must be vcd, csv, saleae or sr");
            }
            std::filesystem::remove(chunk_file);
            bytes = out.bytes();
        }
        std::printf("%s\t%s\t%" PRIu64 "\t%s\t%s\n", bus_id.c_str(), format.c_str(), bytes,
                    bus.decode_args.c_str(), bus.sigrok_args.c_str());
    } catch (const std::exception& e) {
        std::fprintf(stderr, "make_capture: %s\n", e.what());
        return 1;
    }
    return 0;
}
