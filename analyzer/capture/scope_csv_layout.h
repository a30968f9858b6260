#pragma once
// The CSV layouts oscilloscopes write (Rigol, Keysight/Agilent, Tektronix, Siglent,
// PicoScope, LeCroy; docs/contract-scope.md), recognised from the file's first lines:
// where the time comes from (a time column and its unit, or an index column with a start
// and an increment) and which fields hold which channels.
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace busdecode {

struct ScopeChannel {
    std::string name;       // for --map: "CH1", "D12", "A"
    std::string full_name;  // the column title as written; a byte column's bit: its name
    std::size_t field = 0;  // index of its field in a data row
    int bit = -1;           // >= 0: a bit of a digital byte column ("0x10")
    double scale = 1;       // volts per unit of the column: 1e-3 for "(mV)"
};

struct ScopeLayout {
    std::string format;  // "rigol-csv", "keysight-csv", ...
    char sep = ',';
    bool decimal_comma = false;
    std::size_t header_lines = 0;  // lines before the first data row
    std::size_t fields = 0;        // fields of a data row (a trailing empty one tolerated)
    std::size_t time_field = 0;
    double time_scale = 1;       // seconds per unit of the time field
    bool time_is_index = false;  // t = start + index * increment
    double start = 0, increment = 0;
    std::vector<ScopeChannel> channels;
    // LeCroy sequence mode: the data rows come in segments of `segment_rows`, each timed
    // from its own trigger; segment k's times are shifted by segment_starts[k] (seconds
    // after the first trigger). Empty: one segment.
    std::size_t segment_rows = 0;
    std::vector<double> segment_starts;
};

// The layout of `head` (the first bytes of the file; `whole`: all of it), or nullopt when
// it is not a scope CSV. Throws InputError "NAME:LINE: ..." for a broken scope header.
std::optional<ScopeLayout> recogniseScopeCsv(std::string_view head, bool whole,
                                             const std::string& name);

// A number as scopes write it: "+31.0E-03", "  -00.0492", "0,633" (decimal_comma),
// "0x1F". False if it is not one.
bool parseScopeNumber(std::string_view s, bool decimal_comma, double& out);

}  // namespace busdecode
