// Every decoder on hostile traffic: noise on every line, another protocol on its lines,
// a clock with no data, data stuck low, options at the ends of their ranges (64-bit
// words), times near the end of the tick range, a capture with one edge or none. Each
// must decode without crashing or throwing, with events in order and their number
// bounded by the edges (fuzz::decodeChecked checks all of that); a hang shows as the
// test's timeout.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <random>

#include "core/registry.h"
#include "fuzz_harness.h"

namespace busdecode {
namespace {

constexpr Timebase kNs{1, 1'000'000'000};

std::vector<const DecoderFactory*> decoders() {
    fuzz::registerDecoders();
    return Registry::instance().all();
}

bool isClockRole(const std::string& name) {
    return name == "clk" || name == "sclk" || name == "ma";
}

// A waveform on the decoder's roles, in role order (line k = role k).
Waveform blank(const DecoderInfo& info, std::uint8_t level) {
    Waveform w;
    w.timebase = kNs;
    for (const auto& r : info.roles) {
        w.names.push_back(r.name);
        w.initial.push_back(level);
    }
    return w;
}

DecoderRequest requestFor(const DecoderInfo& info,
                          std::map<std::string, std::string> options = {}) {
    DecoderRequest req;
    req.proto = info.id;
    for (const auto& r : info.roles)
        req.map[r.name] = r.name;
    req.options = std::move(options);
    return req;
}

void expectClean(const Waveform& w, const DecoderRequest& req, const std::string& what) {
    // As jsonl reads the events (fields), and as text does (no fields, a summary each).
    for (const bool reads_fields : {true, false}) {
        try {
            const auto stats = fuzz::decodeChecked(w, req, reads_fields);
            EXPECT_FALSE(stats.refused) << req.proto << " refused " << what;
        } catch (const fuzz::HarnessFailure& e) {
            ADD_FAILURE() << req.proto << " on " << what << (reads_fields ? "" : " (as text)")
                          << ": " << e.what();
        }
    }
}

Waveform noise(const DecoderInfo& info, std::uint32_t seed, int edges, Tick max_gap, Tick t0 = 0) {
    Waveform w = blank(info, 1);
    std::mt19937_64 rng(seed);
    std::vector<std::uint8_t> level = w.initial;
    Tick t = t0;
    for (int i = 0; i < edges; ++i) {
        t += Tick(rng() % std::uint64_t(max_gap)) + ((rng() & 7) == 0 ? 0 : 1);  // ties too
        const auto line = std::uint32_t(rng() % w.names.size());
        level[line] ^= 1;
        w.edges.push_back({t, line, level[line]});
    }
    w.start = t0;
    w.end = t + 1000;
    return w;
}

// A square wave on the clock roles (or on line 0 when there is none), the other lines
// held at `others`.
Waveform clockOnly(const DecoderInfo& info, std::uint8_t others, Tick half_period, int cycles) {
    Waveform w = blank(info, others);
    std::vector<std::uint32_t> clocks;
    for (std::size_t r = 0; r < info.roles.size(); ++r)
        if (isClockRole(info.roles[r].name)) clocks.push_back(std::uint32_t(r));
    if (clocks.empty()) clocks.push_back(0);
    for (auto c : clocks)
        w.initial[c] = 1;
    Tick t = 1000;
    for (int i = 0; i < 2 * cycles; ++i, t += half_period)
        for (auto c : clocks)
            w.edges.push_back({t, c, std::uint8_t(i % 2 == 0 ? 0 : 1)});
    w.end = t + 100000;
    return w;
}

// Another protocol's shape: UART-like characters (start bit, 8 data bits, stop) at
// 115200 baud on every line, each line with its own bytes.
Waveform uartOnEveryLine(const DecoderInfo& info, std::uint32_t seed) {
    Waveform w = blank(info, 1);
    std::mt19937 rng(seed);
    const Tick bit = 8681;  // ns at 115200 baud
    std::vector<std::vector<Edge>> per_line(info.roles.size());
    for (std::size_t l = 0; l < info.roles.size(); ++l) {
        std::uint8_t level = 1;
        Tick t = 5000 + Tick(l) * 1234;
        for (int c = 0; c < 200; ++c, t += 12 * bit) {
            const unsigned v = (rng() & 0xff) << 1 | 0x200;  // start bit 0, data, stop bit 1
            for (int b = 0; b < 10; ++b) {
                const std::uint8_t lv = (v >> b) & 1;
                if (lv != level) per_line[l].push_back({t + b * bit, std::uint32_t(l), lv});
                level = lv;
            }
        }
    }
    for (const auto& v : per_line)
        w.edges.insert(w.edges.end(), v.begin(), v.end());
    std::stable_sort(w.edges.begin(), w.edges.end(),
                     [](const Edge& a, const Edge& b) { return a.t < b.t; });
    w.end = w.edges.empty() ? 1000 : w.edges.back().t + 100000;
    return w;
}

// SPI-like traffic (cs low, 10 MHz clock, random data) mapped by position onto the roles.
Waveform spiShapeByPosition(const DecoderInfo& info, std::uint32_t seed) {
    Waveform w = blank(info, 1);
    std::mt19937 rng(seed);
    const std::size_t n = info.roles.size();
    std::vector<std::uint8_t> level = w.initial;
    auto set = [&](std::size_t line, Tick t, std::uint8_t v) {
        if (line >= n || level[line] == v) return;
        level[line] = v;
        w.edges.push_back({t, std::uint32_t(line), v});
    };
    Tick t = 1000;
    for (int word = 0; word < 300; ++word) {
        set(0, t, 0);
        for (int b = 0; b < 32; ++b) {
            set(1, t + 50, 0);
            set(2, t + 52, rng() & 1);
            set(3, t + 53, rng() & 1);
            set(1, t + 100, 1);
            t += 100;
        }
        set(0, t + 50, 1);
        t += 500;
    }
    w.end = t + 100000;
    return w;
}

// Every Int option at its minimum or its maximum (bits = 64 and the like).
std::map<std::string, std::string> extremeOptions(const DecoderInfo& info, bool maximum) {
    std::map<std::string, std::string> out;
    for (const auto& o : info.options) {
        if (o.kind != OptionSpec::Kind::Int || o.key == "glitch_ns") continue;
        const double v = maximum ? std::min(o.max, 1e15) : std::max(o.min, -1e15);
        out[o.key] = fmt::format("{}", std::int64_t(v));
    }
    return out;
}

TEST(HostileTraffic, NoiseOnEveryLine) {
    for (const auto* f : decoders()) {
        const auto& info = f->info();
        expectClean(noise(info, 1, 200000, 400), requestFor(info), "dense noise");
        expectClean(noise(info, 2, 20000, 200000), requestFor(info), "sparse noise");
        expectClean(noise(info, 3, 50000, 400), requestFor(info, {{"glitch_ns", "20"}}),
                    "noise with the glitch filter");
    }
}

TEST(HostileTraffic, WrongProtocolOnTheMappedLines) {
    for (const auto* f : decoders()) {
        const auto& info = f->info();
        expectClean(uartOnEveryLine(info, 4), requestFor(info), "UART characters");
        expectClean(spiShapeByPosition(info, 5), requestFor(info), "SPI words");
    }
}

TEST(HostileTraffic, ClockWithNoData) {
    for (const auto* f : decoders()) {
        const auto& info = f->info();
        expectClean(clockOnly(info, 1, 50, 200000), requestFor(info), "a 10 MHz clock, data high");
        expectClean(clockOnly(info, 1, 500000, 200), requestFor(info), "a 1 kHz clock, data high");
    }
}

TEST(HostileTraffic, DataStuckLow) {
    for (const auto* f : decoders()) {
        const auto& info = f->info();
        expectClean(clockOnly(info, 0, 50, 200000), requestFor(info), "a 10 MHz clock, data low");
    }
}

TEST(HostileTraffic, OptionsAtTheEndsOfTheirRanges) {
    for (const auto* f : decoders()) {
        const auto& info = f->info();
        for (bool maximum : {false, true}) {
            const auto opts = extremeOptions(info, maximum);
            const std::string what = maximum ? "maximal options" : "minimal options";
            try {
                const auto a =
                    fuzz::decodeChecked(noise(info, 6, 50000, 300), requestFor(info, opts));
                const auto b =
                    fuzz::decodeChecked(spiShapeByPosition(info, 7), requestFor(info, opts));
                const auto c =
                    fuzz::decodeChecked(clockOnly(info, 1, 50, 20000), requestFor(info, opts));
                (void)a, (void)b, (void)c;
            } catch (const fuzz::HarnessFailure& e) {
                ADD_FAILURE() << info.id << " with " << what << ": " << e.what();
            }
        }
    }
}

TEST(HostileTraffic, TimesNearTheEndOfTheTickRange) {
    const Tick late = kMaxEdgeTick - 10'000'000'000;  // what an Edge holds, less 10 s at 1 ns
    for (const auto* f : decoders()) {
        const auto& info = f->info();
        expectClean(noise(info, 8, 20000, 300, late), requestFor(info), "noise near 2^55 ticks");
    }
}

TEST(HostileTraffic, OneEdgeOrNone) {
    for (const auto* f : decoders()) {
        const auto& info = f->info();
        for (std::uint32_t line = 0; line < info.roles.size(); ++line) {
            Waveform w = blank(info, 1);
            w.edges.push_back({500, line, 0});
            w.end = 1000;
            expectClean(w, requestFor(info), fmt::format("one edge on {}", info.roles[line].name));
            w.end = 500;  // the capture ends on the edge
            expectClean(w, requestFor(info), "one edge at the very end");
        }
        Waveform none = blank(info, 0);
        none.end = 0;
        expectClean(none, requestFor(info), "an empty capture");
    }
}

}  // namespace
}  // namespace busdecode
