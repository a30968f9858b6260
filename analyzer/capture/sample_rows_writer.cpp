// writeSampleRows: a Waveform as one row per sample, as Vivado's ILA CSV export or a
// ChipScope-style headerless list has it, for round trips through their readers.
#include <fmt/format.h>

#include "capture_writer.h"
#include "core/atomic_file.h"

namespace busdecode {

void writeSampleRows(const Waveform& w, const std::string& path, SampleRowsDialect dialect) {
    if (w.timebase.num <= 0 || w.timebase.den % w.timebase.num != 0 || w.names.size() > 64)
        throw std::invalid_argument(
            "writeSampleRows: needs one sample per tick and at most 64 lines");
    SampleRenderer r(w);
    const std::uint64_t samples = w.end >= w.start ? std::uint64_t(w.end - w.start) + 1 : 0;
    const std::size_t n = w.names.size();
    AtomicFile out(path);
    if (dialect == SampleRowsDialect::VivadoIlaCsv) {
        // Each line as a BINARY probe, and all of them packed in one HEX probe.
        std::string names = "Sample in Buffer,Sample in Window,TRIGGER";
        std::string radix = "Radix - UNSIGNED,UNSIGNED,UNSIGNED";
        for (const auto& name : w.names) {
            names += ",top/u_ila/" + name;
            radix += ",BINARY";
        }
        out.put(fmt::format("{},top/u_ila/lines[{}:0]\n{},HEX\n", names, n - 1, radix));
    }
    std::vector<std::uint8_t> buf(r.unit() * 4096);
    for (std::uint64_t first = 0; first < samples; first += 4096) {
        const std::size_t count = std::size_t(std::min<std::uint64_t>(4096, samples - first));
        r.render(first, count, buf.data());
        std::string text;
        for (std::size_t k = 0; k < count; ++k) {
            std::uint64_t word = 0;
            for (std::size_t b = 0; b < r.unit(); ++b)
                word |= std::uint64_t(buf[k * r.unit() + b]) << (8 * b);
            if (dialect == SampleRowsDialect::VivadoIlaCsv)
                text += fmt::format("{},{},{}", first + k, first + k, first + k == 0 ? 1 : 0);
            for (std::size_t l = 0; l < n; ++l) {
                const char* sep = dialect == SampleRowsDialect::VivadoIlaCsv ? ","
                                  : l == 0                                   ? ""
                                                                             : "\t";
                text += fmt::format("{}{}", sep, (word >> l) & 1);
            }
            if (dialect == SampleRowsDialect::VivadoIlaCsv)
                text += fmt::format(",{:X}\n", word);
            else
                text += "\t\r\n";  // ChipScope's trailing TAB and CRLF
        }
        out.put(text);
    }
    out.commit();
}

}  // namespace busdecode
