#include "ssi_generator.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>

#include "core/bit_word.h"

namespace busdecode {

namespace {

struct Level {
    double t;
    bool level;
};

// What the simulation remembers of one burst to derive its truth afterwards.
struct BurstRecord {
    std::vector<double> falls, rises;
    std::uint64_t word = 0;
    bool reread = false;
    bool level_at_start = true;  // data level the master sees at the first falling edge
    std::vector<std::pair<int, int>> flips;
    std::uint64_t previous_word = 0;  // what a re-read should have repeated
    double rise_at = -1;  // data back high (monoflop expired), -1 if never in the capture
    bool low_at_end = false;
};

// A line's transitions with glitch pulses XOR-ed in (a pulse may even straddle an edge).
std::vector<Level> withGlitches(const std::vector<Level>& base, bool initial,
                                const std::vector<SsiGlitch>& glitches, int line) {
    std::vector<std::pair<double, int>> marks;  // time, +1 glitch starts / -1 ends / 0 base edge
    for (const auto& g : glitches) {
        if (g.line != line) continue;
        marks.push_back({g.at_ns, +1});
        marks.push_back({g.at_ns + g.width_ns, -1});
    }
    if (marks.empty()) return base;
    for (std::size_t i = 0; i < base.size(); ++i)
        marks.push_back({base[i].t, 0});
    std::stable_sort(marks.begin(), marks.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    std::vector<Level> out;
    bool lvl = initial;
    int inside = 0;
    std::size_t bi = 0;
    for (const auto& [t, kind] : marks) {
        if (kind == 0)
            lvl = base[bi++].level;
        else
            inside += kind;
        out.push_back({t, bool(lvl ^ (inside % 2 != 0))});
    }
    return out;
}

// Uniform in [-1, 1) from the raw engine output, the same on every standard library.
double unit(std::mt19937_64& rng) {
    return double(rng() >> 11) * 0x1.0p-53 * 2.0 - 1.0;
}

// The clock and data lines of every burst, before glitches and the capture cut.
struct Simulation {
    std::vector<Level> clk, data;
    std::vector<BurstRecord> bursts;
    double last_clock = 0;
};

Simulation simulateBursts(const SsiGenConfig& cfg, const std::vector<SsiGenFrame>& frames) {
    const int w = cfg.data_bits;
    const int gap = cfg.ring_gap;
    const double T = 1e9 / cfg.clock_hz;
    std::mt19937_64 rng(cfg.seed);

    Simulation sim;
    auto& clk = sim.clk;
    auto& data = sim.data;
    auto& bursts = sim.bursts;
    bool data_level = true;
    double last_clock = cfg.lead_in_ns;
    double pending_rise = -1;  // monoflop expiry as seen on the data line
    std::uint64_t latched = 0;

    auto bitOf = [&](std::uint64_t word, int idx) {  // idx-th bit in wire order
        return cfg.lsb_first ? bool(word >> idx & 1) : bool(word >> (w - 1 - idx) & 1);
    };
    auto setData = [&](double t, bool lvl) {
        if (lvl != data_level) data.push_back({t, lvl});
        data_level = lvl;
    };

    for (const auto& fr : frames) {
        const double t0 = last_clock + fr.pause_ns;
        BurstRecord rec;
        // The encoder's monoflop (retriggered by the clock) still runs: the word stays latched.
        const bool monoflop_running = !bursts.empty() && t0 < last_clock + cfg.tm_ns;
        if (pending_rise >= 0) {
            if (monoflop_running) {
                pending_rise = -1;  // the burst restarts before data returns high
            } else {
                setData(pending_rise, true);
                bursts.back().rise_at = pending_rise;
                pending_rise = -1;
            }
        }
        rec.reread = monoflop_running && !data_level;
        rec.level_at_start = data_level;
        rec.previous_word = latched;
        if (!monoflop_running || fr.relatch) latched = fr.word & lowBits(~std::uint64_t(0), w);
        rec.word = latched;
        rec.flips = fr.flips;

        const int n = fr.clocks > 0 ? fr.clocks : (fr.repeats - 1) * (w + gap) + w + 1;
        auto stream = [&](int k) {  // the bit the encoder shifts out on rising edge k+1
            const int rep = k / (w + gap), idx = k % (w + gap);
            if (idx >= w) return false;
            bool b = bitOf(latched, idx);
            for (const auto& f : fr.flips)
                if (f.first == rep && f.second == idx) b = !b;
            return b;
        };
        for (int i = 0; i < n; ++i) {
            const double f = t0 + i * T + cfg.jitter_ns * unit(rng);
            const double r = t0 + i * T + T / 2 + cfg.jitter_ns * unit(rng);
            clk.push_back({f, false});
            clk.push_back({r, true});
            rec.falls.push_back(f);
            rec.rises.push_back(r);
            setData(r + cfg.delay_ns, stream(i));
        }
        last_clock = rec.rises.back();
        rec.low_at_end = !data_level;
        if (!data_level) pending_rise = last_clock + cfg.tm_ns + cfg.delay_ns;
        bursts.push_back(std::move(rec));
    }
    if (pending_rise >= 0) {
        setData(pending_rise, true);
        bursts.back().rise_at = pending_rise;
    }
    sim.last_clock = last_clock;
    return sim;
}

// Raw word, bit count and repeat comparison of a burst whose data bits were all sampled.
void fullFrameTruth(const SsiGenConfig& cfg, const BurstRecord& b, int d, SsiTruth& t) {
    const int w = cfg.data_bits;
    const int gap = cfg.ring_gap;
    const int lead = cfg.lead ? 1 : 0;
    const bool lead_bit = b.level_at_start;
    t.bits = w + lead;
    t.raw = cfg.lsb_first ? (b.word << lead) | (lead ? std::uint64_t(lead_bit) : 0)
                          : b.word | (lead ? std::uint64_t(lead_bit) << w : 0);
    t.repeats = 1 + (d - w) / (w + gap);
    t.partial_bits = std::max(0, (d - w) % (w + gap) - gap);
    for (const auto& [rep, idx] : b.flips) {
        if (rep < 1 || idx >= w) continue;
        if (rep * (w + gap) + idx >= d) continue;  // never sampled
        t.repeat_match = false;
        t.diff_bits.push_back(cfg.lsb_first ? idx + lead : w - 1 - idx);
    }
    if (b.reread && b.word != b.previous_word) {
        t.repeat_match = false;
        const std::uint64_t d = b.word ^ b.previous_word;
        for (int bit = 0; bit < w; ++bit)
            if (d >> bit & 1) t.diff_bits.push_back(cfg.lsb_first ? bit + lead : bit);
    }
    std::sort(t.diff_bits.begin(), t.diff_bits.end());
    t.diff_bits.erase(std::unique(t.diff_bits.begin(), t.diff_bits.end()), t.diff_bits.end());
}

// What the master saw of one burst, given the clock edges that fall inside the capture.
SsiTruth burstTruth(const SsiGenConfig& cfg, const BurstRecord& b, double end_ns,
                    const WaveBuilder& wb, double ns_per_tick) {
    const int w = cfg.data_bits;
    const int lead = cfg.lead ? 1 : 0;
    SsiTruth t;
    // Clock edges inside the capture decide what the master sampled.
    int n = 0;
    double last = b.falls.front();
    for (std::size_t i = 0; i < b.falls.size(); ++i) {
        if (b.falls[i] >= end_ns) break;
        ++n;
        last = b.falls[i];
        if (b.rises[i] < end_ns) last = b.rises[i];
    }
    t.start = wb.ticksFromNs(b.falls.front());
    t.end = wb.ticksFromNs(last);
    t.reread = b.reread;
    t.clock_hz = cfg.clock_hz;
    const int d = n - 1;  // data samples: falling edges 2..n
    const bool lead_bit = b.level_at_start;
    if (d < w) {
        t.short_frame = true;
        t.bits = d + lead;
        if (cfg.lsb_first)
            t.raw = (lowBits(b.word, d) << lead) | (lead ? std::uint64_t(lead_bit) : 0);
        else
            t.raw = (d == 0 ? 0 : b.word >> (w - d)) | (lead ? std::uint64_t(lead_bit) << d : 0);
    } else {
        fullFrameTruth(cfg, b, d, t);
    }
    if (b.low_at_end && b.rise_at >= 0 && b.rise_at < end_ns && n == int(b.falls.size()))
        t.tm_ns = double(wb.ticksFromNs(b.rise_at) - t.end) * ns_per_tick;
    return t;
}

}  // namespace

SsiGenerated generateSsi(const SsiGenConfig& cfg, const std::vector<SsiGenFrame>& frames) {
    const int w = cfg.data_bits;
    if (w < 1 || w > 64 || w + (cfg.lead ? 1 : 0) > 64)
        throw std::invalid_argument("generateSsi: data_bits out of range");
    const double T = 1e9 / cfg.clock_hz;
    if (cfg.jitter_ns >= T / 4) throw std::invalid_argument("generateSsi: jitter too large");

    const Simulation sim = simulateBursts(cfg, frames);
    const auto clk_edges = withGlitches(sim.clk, true, cfg.glitches, 0);
    const auto data_edges = withGlitches(sim.data, true, cfg.glitches, 1);
    double end_ns = sim.last_clock;
    if (!clk_edges.empty()) end_ns = std::max(end_ns, clk_edges.back().t);
    if (!data_edges.empty()) end_ns = std::max(end_ns, data_edges.back().t);
    end_ns += cfg.tail_ns;
    if (cfg.cut_ns >= 0) end_ns = cfg.cut_ns;

    WaveBuilder wb(Timebase::fromSampleRate(cfg.sample_rate_hz), {cfg.clk_name, cfg.data_name},
                   {1, 1});
    for (const auto& e : clk_edges)
        if (e.t < end_ns) wb.setNs(0, e.t, e.level);
    for (const auto& e : data_edges)
        if (e.t < end_ns) wb.setNs(1, e.t, e.level);

    SsiGenerated out;
    out.wave = wb.build(wb.ticksFromNs(end_ns));
    const double ns_per_tick = out.wave.timebase.nsPerTick();
    for (const auto& b : sim.bursts) {
        if (b.falls.front() >= end_ns) break;
        out.frames.push_back(burstTruth(cfg, b, end_ns, wb, ns_per_tick));
    }
    return out;
}

}  // namespace busdecode
