#pragma once
// The transition-stream model: readers turn samples into level changes of the mapped
// lines only, merged in time order and handed out in fixed-size blocks, so memory stays
// flat whatever the capture length.
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

#include "event.h"
#include "time.h"

namespace busdecode {

// What an edge's packed fields can hold: times within +-2^55 ticks (10 hours at 1 ps,
// 41 days at the 100 ps sigrok writes; readers refuse captures beyond) and 128 selected
// lines (Session refuses more mappings; bench and fuzz tools select the first 128).
inline constexpr Tick kMaxEdgeTick = (Tick(1) << 55) - 1;
inline constexpr Tick kMinEdgeTick = -(Tick(1) << 55);
inline constexpr std::size_t kMaxSelectedLines = 128;
inline constexpr bool edgeTickFits(Tick t) {
    return t >= kMinEdgeTick && t <= kMaxEdgeTick;
}

// The last tick a reader may hand on in timebase `tb`: kMaxEdgeTick, or less where the
// tick's time in ns would pass half of an int64 (146 years, with a $timescale of 1 s or a
// --rate below 1 Hz), so that no event's start_ns or end_ns is clamped without a word.
inline constexpr Tick lastTickOf(const Timebase& tb) {
    if (tb.num <= 0 || tb.den <= 0) return kMaxEdgeTick;
    const __int128 last = __int128(INT64_MAX / 2) * tb.den / (__int128(tb.num) * 1'000'000'000);
    return last < kMaxEdgeTick ? Tick(last) : kMaxEdgeTick;
}

// One edge in 8 bytes, not 16: the reading thread writes every edge and the decoding
// thread reads it on the other core, and moving the blocks between the two cores' caches
// cost time in proportion to their bytes (bench/README.md, "Edges in 8 bytes"). Read the
// fields as before (e.t, e.line, e.level); t sits in the top bits, so that reading it is
// one shift.
struct Edge {
    // Left uninitialised by default: a reader sizes a block to kEdgeBlockSize and fills
    // it through a pointer, without first zeroing 128 KiB per block.
    Edge() noexcept {}  // NOLINT: deliberately not `= default` (that would zero on resize)
    // t within edgeTickFits(), line below kMaxSelectedLines, level 0 or 1: the callers
    // check (readers, Session), not this constructor on every edge. Written as one
    // 8-byte store: three bit-field stores would each read the word first, and a reader
    // writing into a block the other core has just read then waits for those lines to
    // come back (4 times slower at times, as measured).
    Edge(Tick t_, std::uint32_t line_, std::uint8_t level_) noexcept {
        const std::uint64_t word =
            (std::uint64_t(t_) << 8) | (std::uint64_t(line_) << 1) | std::uint64_t(level_ & 1u);
        std::memcpy(static_cast<void*>(this), &word, sizeof word);
    }

    // line * 2 + level: the word's low byte, read in one load (a decoder's dispatch on
    // line and level together, BisscDecoder::dataRun()).
    std::uint32_t lineAndLevel() const noexcept {
        std::uint64_t word;
        std::memcpy(&word, static_cast<const void*>(this), sizeof word);
        return std::uint32_t(word & 0xff);
    }

    std::uint64_t level : 1;  // 0 or 1, the level *after* the edge
    std::uint64_t line : 7;   // index into the reader's selected-line list
    Tick t : 56;
};
static_assert(sizeof(Edge) == 8, "one edge in one 8-byte word");

// One sample of an analog line (scope captures), handed on when a sink draws the trace.
struct VoltSample {
    Tick t;
    float volts;
    std::uint32_t line;  // as Edge::line
};

// The trigger an analog line's edges come from.
struct LineThreshold {
    std::uint32_t line;
    float threshold, hysteresis;  // volts
};

struct EdgeBlock {
    std::vector<Edge> edges;  // time ordered; ties keep reader order
    // Time up to which the capture is known to be complete (>= last edge). Lets
    // decoders close frames on timeouts while a followed file is still growing.
    Tick known_until = kNoTick;
    // What the capture layer found in the signal itself (a differential pair's fault,
    // an analog line's `signal` summary at the end), as events of proto "capture"; rare.
    std::vector<Event> findings;
    // No finding still to come starts before this tick (a pair fault still open since
    // then); kNoTick: none pending. The session holds later events back to keep order.
    Tick findings_from = kNoTick;
    // Analog readers asked for them (OpenOptions::keep_voltages): the samples read for
    // this block, in time order, and the thresholds of their lines.
    std::vector<VoltSample> volts;
    std::vector<LineThreshold> thresholds;
    void clear() {
        edges.clear();
        known_until = kNoTick;
        if (!findings.empty()) findings.clear();
        findings_from = kNoTick;
        volts.clear();
        thresholds.clear();
    }
};

inline constexpr std::size_t kEdgeBlockSize = 16384;

}  // namespace busdecode
