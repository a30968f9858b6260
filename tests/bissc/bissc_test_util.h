#pragma once
// Helpers shared by the BiSS-C tests: decode a generated waveform, pick events by type.
#include <algorithm>
#include <map>
#include <string>
#include <vector>

#include "bissc_decoder.h"
#include "bissc_generator.h"
#include "core/event.h"
#include "core/registry.h"
#include "core/session.h"
#include "core/waveform.h"

namespace busdecode::test {

inline void registerBissc() {
    static const bool registered = [] {
        Registry::instance().add(makeBisscFactory());
        return true;
    }();
    (void)registered;
}

inline std::vector<Event> decodeBissc(const Waveform& w,
                                      const std::map<std::string, std::string>& options,
                                      const std::string& ma = "MA", const std::string& sl = "SLO") {
    registerBissc();
    DecoderRequest r;
    r.proto = "bissc";
    r.map = {{"ma", ma}, {"sl", sl}};
    r.options = options;
    return decodeWaveform(w, {r});
}

// 10 MHz sampled at 100 MS/s, 40 ns of line delay, a 2.04 us timeout and 850 ns of idle:
// frames 6.89 us apart, much as bench/run.sh's BiSS-C capture runs them.
inline BisscGenConfig tenMhzAt100Msps() {
    BisscGenConfig cfg;
    cfg.timebase = Timebase::fromSampleRate(100'000'000);
    cfg.clock_hz = 10e6;
    cfg.line_delay_ns = 40;
    cfg.timeout_ns = 2040;
    cfg.idle_ns = 850;
    return cfg;
}

// `whole` as a capture started at `cut`, as a VCD reader takes it: a line's value on the
// first time line is its level at the start; a line with none there reads 1 until its
// first change.
inline Waveform startingAt(const Waveform& whole, Tick cut) {
    Waveform w = whole;
    std::erase_if(w.edges, [&](const Edge& e) { return e.t < cut; });
    w.start = cut;
    for (std::uint32_t line : {0u, 1u}) {
        auto first = std::find_if(w.edges.begin(), w.edges.end(),
                                  [&](const Edge& e) { return e.line == line; });
        w.initial[line] = first != w.edges.end() && first->t == cut ? first->level : 1;
        if (first != w.edges.end() && (first->t == cut || first->level == 1)) w.edges.erase(first);
    }
    return w;
}

inline std::vector<Event> ofType(const std::vector<Event>& all, const std::string& type) {
    std::vector<Event> out;
    for (const auto& e : all)
        if (e.type == type) out.push_back(e);
    return out;
}

inline std::int64_t intField(const Event& e, const char* key) {
    const Value* v = e.get(key);
    return v ? asInt(*v) : -999;
}

inline bool nullField(const Event& e, const char* key) {
    const Value* v = e.get(key);
    return !v || isNull(*v);
}

}  // namespace busdecode::test
