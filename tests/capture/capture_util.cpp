#include "capture_util.h"

#include <atomic>

#include "capture/vector_range.h"
#include "core/options.h"

namespace busdecode::test {

Collected collect(CaptureReader& r, const std::vector<LineRef>& lines) {
    Collected c;
    c.signals = r.signals();
    c.tb = r.timebase();
    c.format = r.formatName();
    r.select(lines);
    c.initial = r.initialLevels();
    c.start = r.startTick();
    std::vector<std::uint8_t> level = c.initial;
    EdgeBlock b;
    Tick last = kNoTick;
    while (r.next(b)) {
        EXPECT_LE(b.edges.size(), kEdgeBlockSize);
        for (const Edge& e : b.edges) {
            EXPECT_GE(e.t, last) << "edges out of time order";
            last = e.t;
            EXPECT_LT(e.line, lines.size());
            if (level[e.line] == e.level) continue;
            level[e.line] = e.level;
            c.edges.push_back(e);
        }
    }
    c.end = r.endTick();
    return c;
}

Collected collectFile(const std::string& path, const std::vector<std::string>& names,
                      const OpenOptions& opts) {
    auto r = openCapture(path, opts);
    std::vector<LineRef> lines;
    const auto& sigs = r->signals();
    if (names.empty()) {
        for (int i = 0; i < int(sigs.size()); ++i)
            lines.push_back({i, -1});
    } else {
        for (const auto& n : names) {
            int found = -1;
            int bit = -1;
            std::string base = n;
            if (auto lb = n.rfind('['); lb != std::string::npos && n.back() == ']') {
                base = n.substr(0, lb);
                bit = std::stoi(n.substr(lb + 1));
            }
            for (int i = 0; i < int(sigs.size()) && found < 0; ++i)
                if (sigs[i].full_name == n || sigs[i].name == n) found = i, bit = -1;
            for (int i = 0; i < int(sigs.size()) && found < 0; ++i)
                if (sigs[i].full_name == base || sigs[i].name == base) found = i;
            if (found >= 0 && bit >= 0) bit = bitAtIndex(sigs[found], bit).value_or(-1);
            if (found < 0) {
                ADD_FAILURE() << "no signal " << n << " in " << path;
                return {};
            }
            lines.push_back({found, bit});
        }
    }
    return collect(*r, lines);
}

std::string tempCapture(const std::string& name, const std::string& text) {
    std::string p = tempDir() + "/" + name;
    writeFile(p, text);
    return p;
}

std::string errorOf(const std::string& path, const OpenOptions& opts) {
    try {
        collectFile(path, {}, opts);
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

std::vector<NsEdge> inNs(const Collected& c) {
    std::vector<NsEdge> out;
    for (const Edge& e : c.edges)
        out.push_back({c.tb.toNs(e.t), std::uint32_t(e.line), int(e.level)});
    return out;
}

}  // namespace busdecode::test
