#include "bissc_generator.h"

#include <algorithm>
#include <cmath>

#include "core/crc.h"

namespace busdecode {

namespace {

// The slots the slave drives after each rising edge (index 0 = LAT: still idle 1).
std::vector<int> slaveSlots(const BisscFrameSpec& f, int bits, int crc_bits, std::uint32_t crc) {
    std::vector<int> slots = {1, 0};  // LAT, ACK
    for (int i = 0; i < f.proc_cycles; ++i)
        slots.push_back(0);
    slots.push_back(1);  // start
    slots.push_back(f.cds & 1);
    for (int i = bits - 1; i >= 0; --i)
        slots.push_back(int((f.data >> i) & 1));
    slots.push_back(f.ne & 1);
    slots.push_back(f.nw & 1);
    for (int i = crc_bits - 1; i >= 0; --i)
        slots.push_back(int((crc >> i) & 1));
    slots.push_back(0);  // stop
    for (int i = 0; i < f.extra_clocks; ++i)
        slots.push_back(0);
    return slots;
}

}  // namespace

BisscGenerator::BisscGenerator(BisscGenConfig cfg)
    : cfg_(std::move(cfg)), wb_(cfg_.timebase, cfg_.names, {1, 1}), rng_(cfg_.seed) {
    now_ns_ = cfg_.lead_ns;
}

int BisscGenerator::crcBits() const {
    int width = 0;
    for (std::uint32_t p = cfg_.crc_poly; p > 1; p >>= 1)
        ++width;
    return width;
}

std::uint32_t BisscGenerator::crcFor(std::uint64_t data, int ne, int nw) const {
    BitCrc crc = BitCrc::fromFullPoly(cfg_.crc_poly, cfg_.crc_init, cfg_.crc_inverted);
    crc.pushBits(data, cfg_.bits);
    crc.push(ne != 0);
    crc.push(nw != 0);
    return crc.value();
}

double BisscGenerator::jitter() {
    if (cfg_.jitter_ns <= 0) return 0;
    std::uniform_real_distribution<double> d(-cfg_.jitter_ns, cfg_.jitter_ns);
    return d(rng_);
}

void BisscGenerator::setMa(double ns, bool level) {
    ns = std::max(ns, last_ma_ns_);
    last_ma_ns_ = ns;
    wb_.setNs(0, ns, level);
    ma_ = level;
}

void BisscGenerator::setSl(double ns, bool level) {
    ns = std::max(ns, last_sl_ns_);
    last_sl_ns_ = ns;
    wb_.setNs(1, ns, level);
}

const BisscFrameTruth& BisscGenerator::addFrame(const BisscFrameSpec& f) {
    const double period = 1e9 / cfg_.clock_hz;
    const double half = period / 2;
    const int crc_bits = crcBits();
    BisscFrameTruth truth;
    truth.spec = f;
    truth.clock_hz = cfg_.clock_hz;

    std::uint32_t crc = crcFor(f.data, f.ne, f.nw);
    if (f.corrupt_crc) crc ^= 1u;
    truth.crc_sent = crc;
    truth.crc_ok = !f.corrupt_crc;
    const std::vector<int> slots = slaveSlots(f, cfg_.bits, crc_bits, crc);

    int rises = int(slots.size());
    if (f.truncate_after >= 0 && f.truncate_after < rises) {
        rises = f.truncate_after;
        truth.truncated = true;
    }
    truth.rises = rises;

    const double t0 = now_ns_;
    const bool from_hold = !ma_;  // previous frame left MA low (Hold-CDM)
    std::vector<double> rise_t(rises);
    for (int k = 0; k < rises; ++k)
        rise_t[k] = (from_hold ? t0 : t0 + half) + k * period + jitter();
    if (from_hold) rise_t[0] = t0;
    truth.start = wb_.ticksFromNs(t0);

    // MA: fall (unless already low), then low/high phases around each rising edge.
    if (!from_hold) setMa(t0, false);
    for (int k = 0; k < rises; ++k) {
        if (k > 0) setMa(rise_t[k] - half + jitter() * 0.5, false);
        setMa(rise_t[k], true);
    }
    // SL: each slot appears `line_delay` after its rising edge.
    const double d = cfg_.line_delay_ns;
    const int stop = int(slots.size()) - 1 - f.extra_clocks;
    int ready_from = rises;  // first clock the slave, ready again, takes as a new LAT
    if (cfg_.ready_after_stop_ns >= 0 && !truth.truncated) {
        for (int k = stop + 1; k < rises; ++k) {
            if (rise_t[k] > rise_t[stop] + cfg_.ready_after_stop_ns) {
                ready_from = k;
                break;
            }
        }
    }
    for (int k = 1; k < std::min(rises, ready_from); ++k)
        setSl(rise_t[k] + d, slots[k] != 0);
    if (ready_from < rises) {
        truth.retriggered = true;
        setSl(rise_t[stop] + d + cfg_.ready_after_stop_ns, true);
        if (ready_from + 1 < rises) setSl(rise_t[ready_from + 1] + d, false);  // its ACK
    }
    const double last_rise = rises > 0 ? rise_t[rises - 1] : t0;
    // The slave's timeout: SL low (after the stop bit) until timeout after the last clock.
    const double t_end = last_rise + d + cfg_.timeout_ns;
    if (f.cdm && !truth.truncated) setMa(last_rise + half, false);
    setSl(t_end, true);
    truth.end = wb_.ticksFromNs(t_end);
    // Ready early, and no ACK to the clocks after: SL never fell again.
    if (truth.retriggered && ready_from + 1 >= rises)
        truth.end = wb_.ticksFromNs(rise_t[stop] + d + cfg_.ready_after_stop_ns);
    if (!ma_ && !cfg_.hold_cdm) setMa(t_end + std::min(cfg_.idle_ns / 4, 2000.0), true);
    now_ns_ = t_end + cfg_.idle_ns;
    frames_.push_back(truth);
    return frames_.back();
}

void BisscGenerator::addGlitch(int line, double at_ns, double width_ns) {
    glitches_.push_back({line, at_ns, width_ns});
}

Waveform BisscGenerator::build() const {
    Waveform w = wb_.build(wb_.ticksFromNs(now_ns_));
    for (const auto& g : glitches_) {
        const Tick a = wb_.ticksFromNs(g.at_ns);
        const Tick b = std::max(a + 1, wb_.ticksFromNs(g.at_ns + g.width_ns));
        bool level = w.initial[g.line] != 0;
        for (const auto& e : w.edges)
            if (e.line == std::uint32_t(g.line) && e.t <= a) level = e.level != 0;
        w.edges.push_back({a, std::uint32_t(g.line), std::uint8_t(!level)});
        w.edges.push_back({b, std::uint32_t(g.line), std::uint8_t(level)});
    }
    std::stable_sort(w.edges.begin(), w.edges.end(), [](const Edge& x, const Edge& y) {
        return x.t < y.t || (x.t == y.t && x.line < y.line);
    });
    return w;
}

// ---- Control sequences ----

namespace {

struct Bits {
    std::vector<int> cdm, cds;
    void ensure(int n) {
        if (int(cdm.size()) < n) cdm.resize(n, 0);
        if (int(cds.size()) < n) cds.resize(n, 0);
    }
    void putCdm(int f, std::uint32_t v, int n) {
        ensure(f + n);
        for (int i = 0; i < n; ++i)
            cdm[f + i] = int((v >> (n - 1 - i)) & 1);
    }
    void putCds(int f, std::uint32_t v, int n) {
        ensure(f + n);
        for (int i = 0; i < n; ++i)
            cds[f + i] = int((v >> (n - 1 - i)) & 1);
    }
};

// Returns the frame after the item.
int addRegisterAccess(Bits& b, int f0, const ControlItemSpec& it,
                      std::vector<ControlEventTruth>& events) {
    const bool write = it.kind == ControlItemSpec::Kind::Write;
    const std::uint32_t header =
        (1u << 10) | (std::uint32_t(it.id & 7) << 7) | std::uint32_t(it.address & 0x7F);
    std::uint32_t hcrc = bissCrc4(header, 11);
    if (it.corrupt_header_crc) hcrc ^= 1u;
    b.putCdm(f0, 1, 1);  // S
    b.putCdm(f0 + 1, header, 11);
    b.putCdm(f0 + 12, hcrc, 4);
    const std::uint32_t rw = write ? 0b01 : 0b10;
    b.putCdm(f0 + 16, rw, 2);
    b.putCdm(f0 + 18, 1, 1);  // master S
    // Slave: IDL0 = 1 (a single slave takes ID 0), R W echo (W inverted on refusal).
    b.putCds(f0 + 1, 1, 1);
    b.putCds(f0 + 17, it.refuse ? (rw ^ 0b01) : rw, 2);

    int g = f0 + 18;  // frame of the master's S for the current byte
    const int n = std::max<int>(1, int(it.data.size()));
    for (int i = 0; i < n; ++i) {
        const std::uint8_t data = it.data.empty() ? 0 : it.data[i];
        const int busy = i < int(it.busy.size()) ? it.busy[i] : 0;
        ControlEventTruth t;
        t.type = "register";
        t.op = write ? "write" : "read";
        t.id = it.id;
        t.address = (it.address + i) & 0x7F;
        t.first_frame = i == 0 ? f0 : g;
        t.refused = it.refuse;
        if (it.abandon_after_busy >= 0 && busy > it.abandon_after_busy) {
            // The master repeats S for a while, then gives up (CDM back to 0).
            for (int k = 1; k <= it.abandon_after_busy; ++k)
                b.putCdm(g + k, 1, 1);
            const int stop = g + it.abandon_after_busy + 1;
            b.ensure(stop + 1);
            t.last_frame = stop;
            t.busy = it.abandon_after_busy;
            t.crc_ok = false;
            t.error = "abandoned";
            events.push_back(t);
            return stop + 1;
        }
        for (int k = 1; k <= busy; ++k)
            b.putCdm(g + k, 1, 1);  // S repeats, CDS stays 0
        const int fs = g + busy + 1;
        b.putCds(fs, 1, 1);  // slave S
        std::uint32_t dcrc = bissCrc4(data, 8);
        if (it.corrupt_data_crc && i == 0) dcrc ^= 1u;
        if (write) {
            b.putCdm(fs, data, 8);
            b.putCdm(fs + 8, dcrc, 4);
            b.putCdm(fs + 12, 0, 1);    // P
            b.putCds(fs + 1, data, 8);  // echo, with the CRC the slave computes
            b.putCds(fs + 9, bissCrc4(data, 8), 4);
        } else {
            b.putCdm(fs, 0, 13);  // twelve 0s and P
            b.putCds(fs + 1, data, 8);
            b.putCds(fs + 9, dcrc, 4);
        }
        b.putCds(fs + 13, 0, 1);  // slave P
        const bool more = i + 1 < n;
        b.putCdm(fs + 13, more ? 1 : 0, 1);
        t.last_frame = fs + 13;
        t.data = data;
        t.busy = busy;
        t.crc_ok = !it.corrupt_header_crc && !(it.corrupt_data_crc && i == 0);
        if (!t.crc_ok) t.error = "control_crc";
        if (it.refuse) t.error = "refused";
        events.push_back(t);
        g = fs + 13;
    }
    return g + 1;
}

int addCommand(Bits& b, int f0, const ControlItemSpec& it, std::vector<ControlEventTruth>& events) {
    // CTS = 0, IDS0 first, CMD1..0; CRC over CTS + IDS + CMD.
    std::uint32_t bits11 = 0;
    for (int i = 0; i < 8; ++i)
        bits11 = (bits11 << 1) | std::uint32_t((it.ids >> i) & 1);
    bits11 = (bits11 << 2) | std::uint32_t(it.command & 3);
    std::uint32_t crc = bissCrc4(bits11, 11);
    if (it.corrupt_header_crc) crc ^= 1u;
    b.putCdm(f0, 1, 1);
    b.putCdm(f0 + 1, bits11, 11);
    b.putCdm(f0 + 12, crc, 4);
    b.putCdm(f0 + 16, 1, 1);
    for (int i = 0; i < 8; ++i)
        b.putCds(f0 + 17 + i, std::uint32_t((it.ida >> i) & 1), 1);
    ControlEventTruth t;
    t.type = "command";
    t.first_frame = f0;
    t.id = it.ids;
    t.data = it.command;
    t.crc_ok = !it.corrupt_header_crc;
    t.executed = it.execute;
    int last;
    if (it.execute) {
        last = f0 + 16 + it.ex_gap;
        b.putCdm(last, 1, 1);
    } else {
        last = f0 + 16 + 14;
        b.ensure(last + 1);
        t.error = "cancelled";
    }
    if (!t.crc_ok) t.error = "control_crc";
    t.last_frame = last;
    events.push_back(t);
    return last + 1;
}

}  // namespace

ControlSequence buildControlSequence(const std::vector<ControlItemSpec>& items, int trailing_idle) {
    Bits b;
    std::vector<ControlEventTruth> events;
    int f = 0;
    for (const auto& it : items) {
        f += it.idle_before;
        b.ensure(f);
        if (it.kind == ControlItemSpec::Kind::Command)
            f = addCommand(b, f, it, events);
        else
            f = addRegisterAccess(b, f, it, events);
    }
    b.ensure(f + trailing_idle);
    return ControlSequence{b.cdm, b.cds, events};
}

}  // namespace busdecode
