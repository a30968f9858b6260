#pragma once
// SSI decoder: a state machine over the clock and data edges.
//
// A frame is one clock burst: it starts at the first falling clock edge and ends when the
// clock stays high for `gap_bits` clock periods (framing by timeout). The burst's edges
// are kept until then, so the data delay can be measured on the frame itself before its
// bits are sampled (LineSampler, sampling edge + delay). After the burst the data line
// stays low for the monoflop time tm and returns high; the frame is emitted once tm is
// known, a new burst starts while data is still low (a re-read of the same word), or the
// capture ends.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/block_decoding.h"
#include "ssi_config.h"
#include "ssi_word.h"

namespace busdecode {

struct SsiWord;
struct SsiFields;

class SsiDecoder : public BlockDecoder<SsiDecoder> {
public:
    explicit SsiDecoder(const Options& o);
    explicit SsiDecoder(SsiConfig cfg);

    void start(const DecoderContext& ctx) override;
    void edge(Tick t, int role, bool level) override;
    void advance(Tick now) override;
    void finish(Tick end) override;
    // Every frame short by the same count: the words are likely that long.
    std::vector<std::string> advice() const override;
    void glitch(Tick t, int role) override;

private:
    struct DataEdge {
        Tick t;
        bool level;
    };
    struct Burst {
        Tick start = 0;
        std::vector<Tick> falls, rises;
        std::vector<DataEdge> data;  // data edges from the burst start on
        bool data_at_start = true;
        bool reread = false;     // started while data was still low after the last burst
        bool not_ready = false;  // data low at the start, not explained by a re-read
        Tick tp = kNoTick;       // pause since the previous burst's last clock edge
        int filtered_glitches = 0;
        bool overlong = false;
    };
    enum class State { Idle, Clocking, WaitTm };

    void startBurst(Tick t);
    void checkTime(Tick now);
    // A burst is over: its frame made and emitted, or held until tm is known.
    void close(bool capture_end);
    // close()'s steps.
    struct Timing {
        std::int64_t measured = 0;  // median data delay (ticks)
        double delay = 0;           // sampling offset used (ticks)
        bool late = false, sample_late = false;
    };
    // Glitches in the burst; marks the data edges that are.
    int countGlitches(double T, std::vector<std::uint8_t>& data_glitch) const;
    Timing measureTiming(double T, const std::vector<std::uint8_t>& data_glitch);
    // The whole clock periods in the data delay this burst's edges allow, [lo, hi].
    std::pair<int, int> periodRange(double T, std::int64_t frac,
                                    const std::vector<std::uint8_t>& data_glitch) const;
    void checkWindows(double T, std::int64_t frac, int whole, Timing& out,
                      const std::vector<std::uint8_t>& data_glitch) const;
    std::vector<std::uint8_t> sampleBits(double delay) const;
    void fillFrame(Event& e, const SsiWord& w, double T, std::int64_t measured, int glitches);
    std::string frameSummary(const SsiWord& w, const SsiFields& f,
                             const std::vector<std::int64_t>& diff, double T) const;
    // tm: the frame emitted now if data rose after the last clock, else held for it.
    void awaitTm(Tick last, bool capture_end);
    void emitFrame(std::optional<Tick> tm_end, bool deadline_passed);
    double periodTicks() const;
    Tick lastClock() const;
    void emitSummary(Tick end);

    SsiConfig cfg_;
    bool clk_ = true;
    bool data_ = true;
    State state_ = State::Idle;
    Burst b_;
    EventPtr pending_;                // the closed burst's frame, waiting for tm
    bool pending_checks_tm_ = false;  // tm is only checked for complete, unbroken words
    Tick wait_deadline_ = 0;
    Tick last_clock_ = kNoTick;  // last clock edge of the last burst
    double tm_max_ticks_ = 0;    // a burst later than this after it is no re-read
    bool data_rose_since_clock_ = false;
    // measureTiming()'s scratch, kept for its storage: per data edge, the rising edges at
    // or before it; the data delays modulo a period.
    std::vector<std::size_t> rises_before_;
    std::vector<std::int64_t> offsets_;
    int whole_periods_ = -1;   // whole clock periods in the last frame's data delay (-1: none yet)
    bool prev_valid_ = false;  // the previous frame's word, for re-read comparison
    std::uint64_t prev_raw_ = 0;

    // For the summary event.
    std::vector<std::int64_t> tm_values_;
    double clock_min_ = 0, clock_max_ = 0;
    std::int64_t frames_ = 0, mismatches_ = 0, shorts_ = 0, error_frames_ = 0;
    std::int64_t short_bits_ = -1;  // the bits every short frame had (-1: none, or they differ)
    // The ring-shift widths of the first frames (ringWidth(), 0: none), and the one most
    // of them had.
    void noteRingWidth(const std::vector<std::uint8_t>& samples, const SsiWord& w);
    int ringWidthFound() const;
    std::int64_t ring_looked_ = 0;
    std::array<std::int64_t, 65> ring_votes_{};
    std::uint64_t ring_first_raw_ = 0;
    bool ring_varied_ = false;  // the frames looked at held different words
    // Frames clocked past the word by gap bits only (no repeat), all by the same count,
    // and how many of them read a 1 there: a word longer than `bits` (tailAdvice()).
    void noteTail(const std::vector<std::uint8_t>& samples, const SsiWord& w);
    std::vector<std::string> tailAdvice() const;
    std::int64_t tail_frames_ = 0, tail_ones_ = 0;
    int tail_bits_ = 0;  // the bits past the word (-1: they differed)
};

}  // namespace busdecode
