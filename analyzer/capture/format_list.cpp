#include "format_list.h"

#include <fmt/format.h>

#include "core/options.h"
#include "vector_range.h"

namespace busdecode {

const std::vector<FormatEntry>& captureFormats() {
    static const std::vector<FormatEntry> list = {
        {"vcd", "text whose first word is a $keyword ($date, $version, $timescale...)",
         "sigrok, GTKWave, simulators, Vivado ILA VCD"},
        {"fst", "binary header block (type 0, 329 bytes), or a gzip-wrapped FST (type 254)",
         "GTKWave, Verilator; --rate HZ overrides the timescale; scalars and vector bits"},
        {"sigrok-csv", "CSV after sigrok's `; Channels`/`; Samplerate` comments",
         "dense (one row per sample) or with a time column"},
        {"saleae-csv", "CSV whose first column is `Time [s]`", "Logic 1 and Logic 2 exports"},
        {"saleae-bin", "`<SALEAE>`, type 0: digital_N.bin, or a folder of them",
         "Logic 2 binary export, versions 0 and 1; a folder is one capture"},
        {"saleae-bin-analog", "`<SALEAE>`, type 1: analog_N.bin, or a folder of them",
         "versions 0 and 1 (waveforms with gaps); volts through the Schmitt trigger "
         "(--threshold, --hysteresis)"},
        {"csv", "other CSV with a header of names (ScanaStudio, USBee, plain)",
         "without a time column: --rate HZ"},
        {"vivado-ila-csv", "CSV whose second line starts `Radix - `",
         "--rate HZ; vector probes as name[3]; Sample in Buffer/Window, TRIGGER skipped"},
        {"sample-list", "first line only 0/1 fields (spaces, TABs or commas; ChipScope .prn)",
         "--rate HZ; lines named 0, 1, ... by column"},
        {"sigrok-sr", "ZIP holding `metadata` (sigrok session)",
         "logic data; analog channels through the Schmitt trigger"},
        {"dsview-dsl", "ZIP holding `header` (DSView session), device mode 0",
         "logic bit-planes L-<probe>/<block>; --formats FILE shows its decoders"},
        {"dsview-dsl-dso", "the same, device mode 1 (oscilloscope)",
         "8-bit O-<ch>/0 as volts through the Schmitt trigger"},
        {"dsview-dsl-analog", "the same, device mode 2 (analog)",
         "8-bit A-0/<block>, channels interleaved, as volts through the Schmitt trigger"},
        {"rigol-csv", "Rigol scope CSV headers (X,CH1,...,Start,Increment; Time (s); PC software)",
         "DS1000Z/2000/4000, DS1000E/D/B, MSO D7-D0 byte columns; analog lines"},
        {"keysight-csv", "`x-axis,1,2` or per-channel ASCII-XY", "Keysight/Agilent; analog lines"},
        {"tektronix-csv", "`TIME,CH1` or TDS/TBS header rows", "MSO/MDO, TDS/TBS; analog lines"},
        {"siglent-csv", "`Second,` after `Source,` rows", "analog lines"},
        {"lecroy-csv", "`Time,` after LeCroy header rows", "multi-segment too; analog lines"},
        {"picoscope-csv", "`(ms);(V)` units row (PicoScope 6)",
         "`;` separators, decimal commas; analog lines"},
        {"+gzip, +xz, +zstd", "magic bytes 1f 8b / fd 37 7a 58 5a 00 / 28 b5 2f fd",
         "any format above compressed, from a file or standard input"},
        {"(refused) Saleae .sal", "ZIP holding `meta.json`",
         "undocumented: export binary files from Logic 2 instead"},
    };
    return list;
}

void printFormatList(std::FILE* out) {
    fmt::print(out, "Capture formats (recognised by content, not by file name):\n");
    for (const auto& f : captureFormats())
        fmt::print(out, "  {:<22} {}\n  {:<22}   {}\n", f.name, f.recognised_by, "", f.notes);
}

// A capture that has no time of its own (a plain CSV, a sample list) opens only with
// --rate: without one, it is opened again at 1 Hz to say what it is. A file opens twice;
// standard input, read once, does not.
std::unique_ptr<CaptureReader> openToDescribe(const std::string& path, const OpenOptions& opts,
                                              bool& needs_rate) {
    needs_rate = false;
    try {
        return openCapture(path, opts);
    } catch (const InputError&) {
        if (opts.rate_hz > 0 || path == "-") throw;
        OpenOptions at_1hz = opts;
        at_1hz.rate_hz = 1;
        std::unique_ptr<CaptureReader> r;
        try {
            r = openCapture(path, at_1hz);
        } catch (const InputError&) {
        }
        if (!r) throw;  // the first error: the rate was not what it lacked
        needs_rate = true;
        return r;
    }
}

void printCaptureDescription(std::FILE* out, const std::string& path, const OpenOptions& opts) {
    bool needs_rate = false;
    const auto r = openToDescribe(path, opts, needs_rate);
    const Timebase tb = r->timebase();
    const std::string time = needs_rate ? "no time of its own (decode it with --rate HZ)"
                                        : fmt::format("timebase {}/{} s", tb.num, tb.den);
    fmt::print(out, "{}: {}, {}, {} signals\n", path, r->formatName(), time, r->signals().size());
    for (std::size_t i = 0; i < r->signals().size(); ++i) {
        const auto& s = r->signals()[i];
        fmt::print(out, "  {:>3}  {}\n", i, signalText(s));
    }
    for (const auto& note : r->notes())
        fmt::print(out, "  {}\n", note);
}

}  // namespace busdecode
