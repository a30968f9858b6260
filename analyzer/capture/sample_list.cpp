// Headerless sample lists: one row of 0/1 levels per sample, fields separated by spaces,
// TABs or commas (ChipScope `.prn`: `1<TAB>1<TAB><CR><LF>`), no names and no rate. The
// lines are named by their column index from 0; --rate gives the rate.
#include "core/options.h"
#include "readers.h"
#include "sample_rows_reader.h"

namespace busdecode {

namespace {

// Fields of the first non-blank line if all are 0 or 1, else none.
std::size_t levelFields(std::string_view head) {
    std::size_t at = head.find_first_not_of(" \t\r\n");
    if (at == std::string_view::npos) return 0;
    const std::size_t nl = head.find('\n', at);
    if (nl == std::string_view::npos) return 0;  // one whole line at least
    const std::string_view line = head.substr(at, nl - at);
    std::size_t fields = 0;
    for (std::size_t i = 0; i < line.size();) {
        const char ch = line[i];
        if (ch == ' ' || ch == '\t' || ch == ',' || ch == '\r') {
            ++i;
            continue;
        }
        if (ch != '0' && ch != '1') return 0;
        ++fields;
        if (++i < line.size() && line.find_first_of(" \t,\r", i) != i) return 0;
    }
    return fields;
}

}  // namespace

std::unique_ptr<CaptureReader> openSampleList(std::unique_ptr<TextSource>& src,
                                              std::string_view head, const OpenOptions& opts) {
    const std::size_t fields = levelFields(head);
    if (fields == 0) return nullptr;
    SampleColumns c;
    c.dialect = "sample list";
    c.fields = fields;
    c.comma_only = false;
    for (std::size_t i = 0; i < fields; ++i) {
        c.signals.push_back({std::to_string(i), std::to_string(i), 1});
        c.columns.push_back(i);
        c.radix.push_back(SampleColumns::Radix::Binary);
    }
    return sampleRowsReader(std::move(src), std::move(c), opts.rate_hz);
}

}  // namespace busdecode
