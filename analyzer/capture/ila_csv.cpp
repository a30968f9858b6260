// Vivado ILA CSV export: a row of probe names (`Sample in Buffer`, `Sample in Window`,
// `TRIGGER`, then `top/u/probe[7:0]`...), a row of radixes (`Radix - UNSIGNED`, ...,
// `HEX`, `BINARY`) and one row per sample. A multi-bit probe is one vector signal whose
// bits are mapped as `probe[3]`; the counters and TRIGGER are not signals. No rate is
// stated: --rate gives it.
#include <fmt/format.h>

#include "core/options.h"
#include "readers.h"
#include "sample_rows_reader.h"

namespace busdecode {

namespace {

constexpr const char* kDialect = "Vivado ILA CSV";

std::vector<std::string> commaFields(std::string_view line) {
    std::vector<std::string> out;
    for (std::size_t at = 0;;) {
        const std::size_t comma = line.find(',', at);
        std::string_view f = line.substr(at, comma - at);
        while (!f.empty() && (f.front() == ' ' || f.front() == '\t'))
            f.remove_prefix(1);
        while (!f.empty() && (f.back() == ' ' || f.back() == '\t'))
            f.remove_suffix(1);
        out.emplace_back(f);
        if (comma == std::string_view::npos) return out;
        at = comma + 1;
    }
}

// "top/u/bus[7:0]" -> full name "top/u/bus", name "bus", width 8.
SignalInfo probeSignal(const TextSource& src, const std::string& title) {
    SignalInfo s{title, title, 1};
    const auto lb = title.rfind('[');
    const auto colon = title.rfind(':');
    if (lb != std::string::npos && colon != std::string::npos && colon > lb &&
        title.back() == ']') {
        int msb = -1, lsb = -1;
        try {
            msb = std::stoi(title.substr(lb + 1, colon - lb - 1));
            lsb = std::stoi(title.substr(colon + 1));
        } catch (const std::exception&) {
        }
        if (msb < lsb || lsb < 0 || msb - lsb >= 4096)
            throw InputError(src.at(fmt::format("{}: probe '{}' has no [msb:lsb] range I can read",
                                                kDialect, printable(title))));
        s.full_name = title.substr(0, lb);
        s.width = msb - lsb + 1;
    }
    const auto slash = s.full_name.rfind('/');
    s.name = slash == std::string::npos ? s.full_name : s.full_name.substr(slash + 1);
    return s;
}

SampleColumns::Radix radixOf(const TextSource& src, std::string text, const std::string& probe) {
    if (text.rfind("Radix - ", 0) == 0) text = text.substr(8);
    if (text == "HEX") return SampleColumns::Radix::Hex;
    if (text == "BINARY") return SampleColumns::Radix::Binary;
    if (text == "UNSIGNED") return SampleColumns::Radix::Unsigned;
    throw InputError(
        src.at(fmt::format("{}: probe '{}' is in radix '{}': export it as HEX, BINARY or UNSIGNED",
                           kDialect, printable(probe), printable(text))));
}

bool isIla(std::string_view head) {
    const auto nl = head.find('\n');
    return nl != std::string_view::npos && head.substr(nl + 1).rfind("Radix - ", 0) == 0;
}

}  // namespace

std::unique_ptr<CaptureReader> openIlaCsv(std::unique_ptr<TextSource>& src, std::string_view head,
                                          const OpenOptions& opts) {
    if (!isIla(head)) return nullptr;
    std::string_view line;
    src->nextLine(line);
    const auto names = commaFields(line);
    src->nextLine(line);
    const auto radixes = commaFields(line);
    if (radixes.size() != names.size())
        throw InputError(src->at(
            fmt::format("{}: {} radixes for {} probes", kDialect, radixes.size(), names.size())));
    SampleColumns c;
    c.dialect = kDialect;
    c.fields = names.size();
    for (std::size_t i = 0; i < names.size(); ++i) {
        if (names[i] == "Sample in Buffer" || names[i] == "Sample in Window" ||
            names[i] == "TRIGGER")
            continue;
        c.signals.push_back(probeSignal(*src, names[i]));
        c.columns.push_back(i);
        c.radix.push_back(radixOf(*src, radixes[i], names[i]));
    }
    if (c.signals.empty())
        throw InputError(src->at(1, fmt::format("{}: no probe columns", kDialect)));
    return sampleRowsReader(std::move(src), std::move(c), opts.rate_hz);
}

}  // namespace busdecode
