#pragma once
// Writes an in-memory Waveform as a capture file the way real tools do: generators use
// these to make the example captures in captures/ and the inputs of differential tests.
// Files are written atomically (temporary file, then rename).
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "capture/compression.h"
#include "core/waveform.h"

namespace busdecode {

// VCD with sigrok's dialect (several changes on one timestamp line, `$timescale` from
// the waveform's timebase when it is a power of ten, else 1 ps).
void writeVcd(const Waveform& w, const std::string& path);

enum class CsvDialect {
    SigrokDense,   // `; Channels (n/m): A, B` + `; Samplerate: X` comments, `logic,...` header, one
                   // row per sample
    SaleaeLogic2,  // `Time [s],A,B`, one row per change
    Plain,         // header of names, one row per sample (needs --rate to read back)
};
// Dense dialects need a timebase that is one sample per tick (Timebase::fromSampleRate).
void writeCsv(const Waveform& w, const std::string& path, CsvDialect dialect);

// A sigrok session (.sr) as PulseView and `sigrok-cli -O srzip` write it: deflated
// 4 MiB chunks of samples, 1 to 64 lines (unitsize 1 to 8). Needs a timebase of one
// sample per tick. Throws InputError naming the file when it cannot be written.
void writeSr(const Waveform& w, const std::string& path);

// The same from a sample source: render(first, n, out) writes samples first .. first+n-1
// (unitsize = ceil(lines / 8) bytes each, little-endian, line i in bit i) to out; it is
// called once per 4 MiB chunk, in order. For captures longer than a Waveform can hold.
using SrSampleWriter = std::function<void(std::uint64_t first, std::size_t n, std::uint8_t* out)>;
void writeSrSamples(const std::string& path, const std::vector<std::string>& names,
                    std::int64_t rate, std::uint64_t samples, const SrSampleWriter& render);

// A waveform's dense samples as a session stores them (line i in bit i, unitsize =
// ceil(lines / 8) bytes each, little-endian), stretch by stretch: render(first, n, out)
// writes the samples of ticks start+first .. start+first+n-1. In order it carries its
// place from one stretch to the next; an earlier stretch starts it over.
class SampleRenderer {
public:
    explicit SampleRenderer(const Waveform& w);
    std::size_t unit() const { return unit_; }
    void render(std::uint64_t first, std::size_t n, std::uint8_t* out);

private:
    const Waveform& w_;
    std::size_t unit_;
    std::uint64_t start_levels_ = 0, levels_ = 0;  // bit i = line i
    std::size_t k_ = 0;                            // next edge
    Tick at_ = 0;                                  // tick after the last stretch
};

// A DSView session (.dsl): one bit-plane per line and block of 2^24 samples. Needs a
// timebase of one sample per tick; holds the planes in memory (generated traffic).
void writeDsl(const Waveform& w, const std::string& path);

// One row per sample: Vivado's ILA CSV export (each line a BINARY probe `top/u_ila/NAME`
// and all of them in the HEX probe `top/u_ila/lines[n-1:0]`) or a headerless list as
// ChipScope's .prn (TAB after each level, CRLF). Needs one sample per tick, 64 lines at most.
enum class SampleRowsDialect { VivadoIlaCsv, ChipScopePrn };
void writeSampleRows(const Waveform& w, const std::string& path, SampleRowsDialect dialect);

// Saleae Logic 2's binary export of the lines: `dir`/digital_N.bin, version 0 or 1.
void writeSaleaeBin(const Waveform& w, const std::string& dir, int version);
// The lines as Saleae's analog export, `dir`/analog_N.bin: one float sample per tick (a
// timebase of one sample per tick), `volts` for a high level, 0 for a low; version 1
// splits the samples into two waveforms, the second beginning where the first ends.
void writeSaleaeAnalogBin(const Waveform& w, const std::string& dir, double volts, int version = 0);

// An FST file (fstapi's writer): the lines as 1-bit wires, ticks exact in a power-of-ten
// timescale where one holds them (an 80 ns tick: 10 ns units), else rounded to 1 fs.
void writeFst(const Waveform& w, const std::string& path);

// `in_path` compressed into `out_path` as gzip, xz or zstd (not None) write it.
void compressFile(const std::string& in_path, const std::string& out_path, Compression kind);

// A sample rate as sigrok writes it ("100 MHz", "250 kHz", "5 Hz").
std::string sampleRateText(std::int64_t hz);

}  // namespace busdecode
