#pragma once
// Helpers for the reader tests: write a small capture, open it, collect all edges.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "capture/capture_reader.h"
#include "core/options.h"
#include "support/paths.h"

namespace busdecode {
inline bool operator==(const Edge& a, const Edge& b) {
    return a.t == b.t && a.line == b.line && a.level == b.level;
}
inline std::ostream& operator<<(std::ostream& os, const Edge& e) {
    return os << "{" << e.t << "," << e.line << "," << int(e.level) << "}";
}
}  // namespace busdecode

namespace busdecode::test {

struct Collected {
    std::vector<SignalInfo> signals;
    Timebase tb;
    std::string format;
    std::vector<std::uint8_t> initial;
    Tick start = 0, end = 0;
    std::vector<Edge> edges;  // only real changes (repeats dropped, as the session does)
};

// Reads everything from `r` with `lines` selected.
Collected collect(CaptureReader& r, const std::vector<LineRef>& lines);
// Opens `path` and selects the signals by name (or all signals when `names` is empty).
Collected collectFile(const std::string& path, const std::vector<std::string>& names = {},
                      const OpenOptions& opts = {});
// Writes `text` to a fresh file in the test's temp dir and returns its path.
std::string tempCapture(const std::string& name, const std::string& text);
// The InputError message of opening and reading `path` all through ("" if none).
std::string errorOf(const std::string& path, const OpenOptions& opts = {});

// Edges as (ns, line, level) for comparing captures with different timebases.
struct NsEdge {
    std::int64_t ns;
    std::uint32_t line;
    int level;
    bool operator==(const NsEdge&) const = default;
};
inline std::ostream& operator<<(std::ostream& os, const NsEdge& e) {
    return os << "{" << e.ns << "ns," << e.line << "," << e.level << "}";
}
std::vector<NsEdge> inNs(const Collected& c);

}  // namespace busdecode::test
