// A BiSS-C pass over a whole frame's edges at once, timed on one capture's edges held in
// memory (no file, no tokenising), against the decoder itself on the same edges: how
// fast the design bench/README.md named as the one left untried could decode. An
// experiment, not part of `decode`: it keeps only what make_capture's BiSS-C files need
// (MA named "ma", SL named "sl", 26 position bits, CRC6, no register traffic, no faults,
// no events), and it measures the frame's delay and period once the frame has ended
// instead of edge by edge, so its sample times are not the decoder's bit for bit. What
// it times is a floor for that design, not a decoder.
//
//     bissc_frame_experiment FILE [RUNS] [BITS]
//
// - frame-at-once: every edge once, in two steps per frame:
//   - collect: each edge stored as an MA rise and as an SL edge (tick * 2 + level), with
//     no branch on which it is (both stores made, each count moved on by 0 or 1); a
//     pause in MA longer than kQuietTicks ends the frame. SL's edges after the frame's
//     clock (its timeout's end) stay with it.
//   - sample: the ACK (SL's first fall after the second rise) gives the line delay; the
//     frame's SL edges refine it (the mean of those within half a period of it); the
//     period is the mean over all the frame's rises. Slot k is read at rise k + delay +
//     T/2: each SL edge finds the first slot it changes on its own (no chain from edge
//     to edge), its bit is set in a 128-bit word of toggles, and the slots' levels are
//     the running XOR of the toggles (seven shifts). The fields are cut from that word
//     with shifts, the CRC checked through the decoder's table (FixedLengthCrc).
// - collect-only: the first step alone (what this design pays to touch the edges).
// - decoder: BisscDecoder on the same edges, in decode's blocks through edges(), its
//   events counted and dropped, their fields not asked for (as decode's text output).
// - touch-only: every edge read and summed (memory's part).
// Each prints the median of RUNS (default 5) passes in ns per edge and per frame, and
// the frames, clean frames and the sum of their positions, to check against `decode
// FILE --proto bissc --format jsonl` (bench/README.md has the command).
#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <vector>

#include "bench_captures.h"
#include "bissc_decoder.h"
#include "capture/capture_reader.h"
#include "core/block_decoding.h"
#include "core/crc.h"
#include "core/options.h"
#include "core/registry.h"
#include "read_edges.h"

namespace {

using busdecode::Edge;
using busdecode::EdgeBlock;
using busdecode::Tick;

// MA silent this long (ticks) ends a frame: a few clock periods at 10 MHz and 100 MS/s
// (make_capture's frames are 1 us of idle plus the slave's 2 us timeout apart).
constexpr Tick kQuietTicks = 100;
// Rises and SL edges a frame may hold; a longer one is dropped (counted as `overlong`).
constexpr std::size_t kMaxFrameEdges = 4096;  // (a multiple of run()'s kGroup)

struct Totals {
    std::uint64_t frames = 0;
    std::uint64_t clean = 0;  // ACK low, a start bit, CRC right, stop bit low
    std::uint64_t position_sum = 0;
    std::uint64_t overlong = 0;
};

struct Edges {
    std::vector<Edge> edges;
    int ma = -1, sl = -1;  // their lines (the low byte's line: lineAndLevel() / 2)
    bool ma_initial = true, sl_initial = true;  // their levels before the first edge
    busdecode::Timebase timebase;
};

// Every signal selected (read_edges.h), each signal's line its index: make_capture's
// BiSS-C files have only MA and SL.
Edges loadEdges(const std::string& path) {
    busdecode::OpenOptions one_thread;
    one_thread.read_file_ahead = false;
    auto reader = busdecode::bench::openSelected(path, one_thread);
    Edges out;
    const auto& signals = reader->signals();
    for (int i = 0; i < int(signals.size()); ++i) {
        if (signals[std::size_t(i)].name == "ma") out.ma = i;
        if (signals[std::size_t(i)].name == "sl") out.sl = i;
    }
    if (out.ma < 0 || out.sl < 0 || signals.size() != 2) {
        std::fprintf(stderr, "%s: not two signals named ma and sl (make_capture bissc)\n",
                     path.c_str());
        std::exit(2);
    }
    out.timebase = reader->timebase();
    const std::vector<std::uint8_t> initial = reader->initialLevels();
    out.ma_initial = initial[std::size_t(out.ma)] != 0;
    out.sl_initial = initial[std::size_t(out.sl)] != 0;
    EdgeBlock block;
    while (reader->next(block))
        out.edges.insert(out.edges.end(), block.edges.begin(), block.edges.end());
    return out;
}

class FramePass {
public:
    FramePass(const Edges& in, int bits)
        : in_(in),
          bits_(bits),
          crc_(busdecode::BitCrc::fromFullPoly(0x43, 0, true), bits + 2),
          rises_(kMaxFrameEdges),
          sl_(kMaxFrameEdges) {}

    template <bool kSample>
    [[gnu::noinline]] Totals run() {
        Totals totals;
        // Keys: the edge's low byte, line * 2 + level.
        const unsigned ma_rise = unsigned(in_.ma) * 2u + 1u;
        const unsigned sl_line = unsigned(in_.sl);
        // The storage in locals: members would be reloaded after every store.
        Tick* const rises = rises_.data();
        Tick* const sl = sl_.data();
        std::size_t nr = 0, ns = 0;
        Tick last_ma = in_.edges.empty() ? 0 : in_.edges.front().t;
        bool sl_before = in_.sl_initial;  // SL's level before the frame's first SL edge
        // In groups of kGroup edges, the room for them tested once a group: each edge adds
        // one to nr or ns at most.
        constexpr std::size_t kGroup = 64;
        const Edge* e = in_.edges.data();
        const Edge* const end = e + in_.edges.size();
        while (e != end) {
            if (nr + kGroup > kMaxFrameEdges || ns + kGroup > kMaxFrameEdges) [[unlikely]] {
                ++totals.overlong;
                nr = ns = 0;
            }
            const Edge* const group_end = end - e > std::ptrdiff_t(kGroup) ? e + kGroup : end;
            for (; e != group_end; ++e) {
                const Tick t = e->t;
                const unsigned key = e->lineAndLevel();
                const bool is_sl = (key >> 1) == sl_line;
                // A frame's first MA edge. The test of the time first: a test of the role
                // first would be a branch on data (SL's edges come at random),
                // mispredicted at every other bit; the time is far from the last MA edge
                // twice a frame.
                if (t - last_ma > kQuietTicks) [[unlikely]] {
                    if (!is_sl) {
                        if constexpr (kSample) sampleFrame(nr, ns, sl_before, totals);
                        if (ns > 0) sl_before = (sl[ns - 1] & 1) != 0;
                        nr = ns = 0;
                    }
                }
                rises[nr] = t;
                nr += key == ma_rise;
                sl[ns] = t * 2 + Tick(key & 1u);
                ns += is_sl;
                last_ma = is_sl ? last_ma : t;
            }
        }
        if constexpr (kSample) sampleFrame(nr, ns, sl_before, totals);
        if constexpr (!kSample) totals.frames = nr + ns;  // (kept live)
        return totals;
    }

private:
    void sampleFrame(std::size_t nr, std::size_t ns, bool sl_before, Totals& totals) {
        if (nr < 2) return;
        ++totals.frames;
        const Tick* r = rises_.data();
        const Tick* sl = sl_.data();  // each SL edge as tick * 2 + level
        // The ACK: SL's first fall after the second rise.
        std::size_t j = 0;
        while (j < ns && ((sl[j] >> 1) <= r[1] || (sl[j] & 1) != 0))
            ++j;
        if (j == ns) return;
        const double period = double(r[nr - 1] - r[0]) / double(nr - 1);
        if (!(period > 0)) return;  // rises in one tick: no slot can be placed
        const double half = period / 2.0;
        const double ack_delay = double((sl[j] >> 1) - r[1]);
        // Each later SL edge answers the rise nearest to it less the delay.
        double delay_sum = ack_delay;
        double delay_edges = 1;
        const double inv_period = 1.0 / period;
        for (std::size_t i = j + 1; i < ns; ++i) {
            // The nearest rise, by truncation of k + 0.5 (SSE2 has no rounding instruction:
            // nearbyint() would be a call), clamped to the frame's rises.
            const double k = (double((sl[i] >> 1) - r[0]) - ack_delay) * inv_period + 0.5;
            const std::size_t rise = std::size_t(std::clamp(k, 0.0, double(nr - 1)));
            const double offset = double((sl[i] >> 1) - r[rise]);
            const bool near = std::fabs(offset - ack_delay) < half;
            delay_sum += near ? offset : 0.0;
            delay_edges += near ? 1.0 : 0.0;
        }
        const double delay = delay_sum / delay_edges;
        // Slots 1 .. nr-1 (1 = ACK), MSB first (slot k is bit slots - k), SL's level at
        // each sample time: SL's level before the frame, changed by each SL edge from the
        // first slot sampled at or after it on. Each edge finds that slot on its own (no
        // chain from one edge or slot to the next, as a merge would have): estimated from
        // the mean period, then moved to the exact slot; its bit in `toggles` is set, and
        // the levels are the XOR of the toggles from each slot back to the first.
        const std::size_t slots = std::min<std::size_t>(nr - 1, 127);
        const double offset = delay + half;  // a sample's time after its rise
        const auto at = [&](std::size_t k) { return double(r[k]) + offset; };
        unsigned __int128 toggles = 0;
        for (std::size_t i = 0; i < ns; ++i) {
            const double u = double(sl[i] >> 1);
            const double estimate = (u - double(r[0]) - offset) * inv_period + 1.0;
            std::size_t k = std::size_t(std::clamp(estimate, 1.0, double(slots)));
            while (k <= slots && at(k) < u)  // (rarely: the estimate is nearly always right)
                ++k;
            while (k > 1 && at(k - 1) >= u)
                --k;
            if (k > slots) continue;  // after the last sample (the timeout's end)
            toggles ^= (unsigned __int128)(1) << (slots - k);
        }
        unsigned __int128 word = toggles;  // each bit: the XOR of it and those above it
        for (int shift = 1; shift < 128; shift *= 2)
            word ^= word >> shift;
        if (sl_before) word ^= ((unsigned __int128)(1) << slots) - 1;
        // Slot k is bit slots - k. After the ACK (low), busy slots are low until Start.
        if ((word >> (slots - 1)) & 1u) return;  // no ACK
        const unsigned __int128 after_ack = word & (((unsigned __int128)(1) << (slots - 1)) - 1);
        if (after_ack == 0) return;  // no start bit
        const auto hi = std::uint64_t(after_ack >> 64);
        const int start_bit =
            hi != 0 ? 127 - std::countl_zero(hi) : 63 - std::countl_zero(std::uint64_t(after_ack));
        // Start, CDS, data, nE, nW, CRC6, stop: bits_ + 11 slots from the start bit on.
        const int fields = bits_ + 11;
        if (start_bit + 1 < fields) return;  // a short frame
        const auto frame = std::uint64_t(word >> (start_bit + 1 - fields));
        const bool stop_low = (frame & 1u) == 0;
        const std::uint32_t crc_rx = std::uint32_t(frame >> 1) & 0x3Fu;
        const std::uint64_t message = (frame >> 7) & ((std::uint64_t(1) << (bits_ + 2)) - 1);
        const std::uint64_t position = message >> 2;
        if (stop_low && crc_.of(message) == crc_rx) {
            ++totals.clean;
            totals.position_sum += position;
        }
    }

    const Edges& in_;
    int bits_;
    busdecode::FixedLengthCrc crc_;
    std::vector<Tick> rises_;
    std::vector<Tick> sl_;  // the frame's SL edges, each as tick * 2 + level
};

// The decoder itself on the same edges, in decode's blocks (kEdgeBlockSize) through
// edges(), its events counted and dropped, their fields not asked for (decode's text
// output): what its runs (dataRun()) and the rest of its per-frame work cost in memory.
class DecoderPass {
public:
    DecoderPass(const Edges& in, int bits) : in_(in) {
        busdecode::bench::registerDecoders();
        factory_ = busdecode::Registry::instance().find("bissc");
        options_ = busdecode::Options::resolve(factory_->info(), {{"bits", std::to_string(bits)}});
        role_of_line_.assign(std::size_t(std::max(in.ma, in.sl) + 1), -1);
        role_of_line_[std::size_t(in.ma)] = busdecode::BisscDecoder::kMa;
        role_of_line_[std::size_t(in.sl)] = busdecode::BisscDecoder::kSl;
    }

    std::uint64_t run() {
        struct Counting : busdecode::EventSink {
            std::uint64_t events = 0;
            void onEvent(busdecode::Event&&) override { ++events; }
        } sink;
        std::unique_ptr<busdecode::Decoder> owned = factory_->create(options_);
        busdecode::FastDecoder* decoder = busdecode::fastPathOf(*owned);
        busdecode::DecoderContext ctx;
        ctx.timebase = in_.timebase;
        ctx.sink = &sink;
        decoder->setHints({false, busdecode::linesAreRoles(role_of_line_)});
        ctx.initial_levels = {in_.ma_initial ? 1 : 0, in_.sl_initial ? 1 : 0};  // MA, SL
        decoder->start(ctx);
        const Edge* e = in_.edges.data();
        const std::size_t n = in_.edges.size();
        for (std::size_t i = 0; i < n; i += busdecode::kEdgeBlockSize)
            decoder->edges(e + i, e + std::min(i + busdecode::kEdgeBlockSize, n),
                           role_of_line_.data());
        decoder->finish(n > 0 ? in_.edges.back().t + 1000 : 0);
        return sink.events;
    }

private:
    const Edges& in_;
    const busdecode::DecoderFactory* factory_ = nullptr;
    busdecode::Options options_;
    std::vector<int> role_of_line_;
};

template <class F>
double medianSeconds(int runs, F&& pass) {
    std::vector<double> times;
    for (int i = 0; i < runs; ++i) {
        const auto t0 = std::chrono::steady_clock::now();
        pass();
        times.push_back(
            std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    }
    std::sort(times.begin(), times.end());
    return times[times.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2 || argc > 4) {
        std::fprintf(stderr, "usage: bissc_frame_experiment FILE [RUNS] [BITS]\n");
        return 2;
    }
    const int runs = argc > 2 ? std::max(1, std::atoi(argv[2])) : 5;
    const int bits = argc > 3 ? std::atoi(argv[3]) : 26;
    if (bits < 1 || bits > 52) {
        std::fprintf(stderr, "bissc_frame_experiment: BITS must be 1..52\n");
        return 2;
    }
    Edges in;
    try {
        in = loadEdges(argv[1]);
    } catch (const std::exception& e) {  // the reader's one-line error (file and line)
        std::fprintf(stderr, "%s\n", e.what());
        return 2;
    }
    FramePass pass(in, bits);
    Totals totals;
    std::uint64_t touched = 0, events = 0;
    DecoderPass decoder(in, bits);
    const double decoder_s = medianSeconds(runs, [&] { events = decoder.run(); });
    const double touch_s = medianSeconds(runs, [&] {
        std::uint64_t sum = 0;
        for (const Edge& e : in.edges)
            sum += std::uint64_t(e.t) ^ e.lineAndLevel();
        touched = sum;
    });
    const double sampled_s = medianSeconds(runs, [&] { totals = pass.run<true>(); });
    const double collect_s = medianSeconds(runs, [&] { (void)pass.run<false>(); });
    const double n = double(in.edges.size());
    const double frames = double(std::max<std::uint64_t>(totals.frames, 1));
    std::printf("edges %zu frames %llu clean %llu position_sum %llu overlong %llu\n",
                in.edges.size(), (unsigned long long)totals.frames,
                (unsigned long long)totals.clean, (unsigned long long)totals.position_sum,
                (unsigned long long)totals.overlong);
    std::printf("frame-at-once  %.3f s  %.2f ns/edge  %.0f ns/frame\n", sampled_s,
                sampled_s * 1e9 / n, sampled_s * 1e9 / frames);
    std::printf("collect-only   %.3f s  %.2f ns/edge  %.0f ns/frame\n", collect_s,
                collect_s * 1e9 / n, collect_s * 1e9 / frames);
    std::printf("decoder        %.3f s  %.2f ns/edge  %.0f ns/frame  (%llu events)\n", decoder_s,
                decoder_s * 1e9 / n, decoder_s * 1e9 / frames, (unsigned long long)events);
    std::printf("touch-only     %.3f s  %.2f ns/edge  (%llu)\n", touch_s, touch_s * 1e9 / n,
                (unsigned long long)touched);
    return 0;
}
