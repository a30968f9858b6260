#pragma once
// BiSS-C (continuous mode, point to point) from the master clock MA and the slave line
// SL, as seen at the master. Per frame (docs/protocols.md §1.1):
//   MA falls (or, with Hold-CDM, rises from low); the 1st rising edge latches (LAT); the
//   slave pulls SL low after the 2nd rising edge (ACK), keeps it low while busy, then
//   sends Start = 1, CDS, data MSB first, nE, nW, CRC (inverted), and a 0 stop bit; SL
//   stays low for the slave's timeout, then rises. CDM = inverted MA level then.
// The line delay d is measured per frame from the 2nd rising MA edge to the falling SL
// edge, and every bit is sampled at its MA rising edge + d + T/2: SL is read where the
// slave's answer really is, however long the cable (d may span many bit times).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "bissc_control.h"
#include "bissc_options.h"
#include "core/block_decoding.h"
#include "core/crc.h"
#include "core/line_sampler.h"
#include "core/registry.h"
#include "core/splice_words.h"
#include "core/splicing.h"
#include "rise_list.h"

namespace busdecode {

class BisscDecoder : public FastDecoder, public SpliceableDecoder {
public:
    enum Role { kMa = 0, kSl = 1 };

    explicit BisscDecoder(const Options& options);

    void start(const DecoderContext& ctx) override;
    // One edge: a frame's usual data edge through takeDataEdge(), a clock edge before the
    // ACK through takeAckWaitEdge(), any other through the general path (edgeReference()).
    void edge(Tick t, int role, bool level) override;
    // A block of edges: the runs of a frame's data through dataRun(), the clock edges
    // before the ACK through takeAckWaitEdge(), every other edge through the general path.
    void edges(const Edge* first, const Edge* last, const int* role_of_line) override;
    // The general path alone, for every edge: samples scheduled in the LineSampler and
    // taken as SL's edges and time pass them. What dataRun() is tested against.
    void edgeReference(Tick t, int role, bool level) override;
    void advance(Tick now) override;
    void finish(Tick end) override;
    void glitch(Tick t, int role) override;
    Tick watermark(Tick now) const override;
    // Advice when fewer than one in eight answered frames came out clean (see
    // cleanFrames()): the data width, the CRC options or the mapping is the likely cause;
    // or when the lines change but no frame is answered: the mapping.
    std::vector<std::string> advice() const override;
    // advice()'s part on the frames decoded (the mapping, the width, the CRC).
    std::vector<std::string> framingAdvice() const;
    // Splice points (core/piece_speculation.h): at a frame's first clock edge (no rise
    // yet) or idle, with no sample waiting and no control access open; every field
    // compared but the running totals (bissc_splice.cpp).
    bool spliceState(SpliceState& out) const override;
    void addCounts(const std::vector<std::uint64_t>& delta) override;
    // Outside a control access, with the preamble of CDM zeros seen: what every capture
    // without register traffic has been in since its 14th frame.
    void guessHistory() override { control_.assumePreambleSeen(); }

    // Frames the slave answered (an ACK), and of those the clean ones: the CRC right, the
    // stop bit low, no fault but those the encoder reports itself (nE, nW) or that do not
    // depend on the framing (timeout_short, glitch). A wrong data width makes nearly every
    // frame unclean (the width finder picks the width with the most clean frames).
    std::uint64_t answeredFrames() const { return answered_frames_; }
    std::uint64_t cleanFrames() const { return clean_frames_; }

private:
    enum class State {
        WaitSlaveIdle,  // SL low outside a frame: wait for it to rise
        Idle,           // SL high, no frame
        WaitAck,        // clocking, waiting for SL to fall (ACK)
        Data,           // ACK seen: sampling the frame's slots
        Timeout,        // stop bit seen: waiting for SL to rise (end of the slave's timeout)
        TimeoutEnded,   // SL rose: is the master's clock still running (clocks past the stop)?
    };
    // Where the slot parser is within the frame.
    enum class Slot { Ack, Busy, Cds, Data, NE, NW, Crc, Stop, Done };

    // The state a frame's usual data edge reads and writes (takeDataEdge()), declared
    // once: a run of edges copies it whole into a local, which the compiler keeps in
    // registers, and back (dataRun()); a single edge works on the member (edge()). The
    // line levels carry over from frame to frame, the rest is the frame's (beginFrame()).
    // Laid out without padding and with no two doubles side by side: GCC copies a struct
    // with padding through memory, and packs two adjacent doubles of a copied struct into
    // one vector register, unpacked again at every edge (dataRun() checks the padding).
    struct RunFields {
        Tick last_ma_edge = kNoTick;
        double delay = 0;           // line delay in ticks: mean over the SL edges so far
        std::size_t scheduled = 1;  // rises with a scheduled sample (index 0 = LAT has none)
        double delay_sum = 0;
        // Longest MA clock phases (ticks) after LAT until the ACK (masterGaveUp()), then
        // from the ACK on: the clock as it really runs, which a pause before the ACK (a
        // frame whose start was missed) cannot stretch (isClockPhase()).
        Tick max_high = 0;
        double delay_edges = 0;  // a count, held as the divisor it is used as
        Tick max_low = 0;
        double last_sample_t = -1e300;
        std::uint64_t data = 0;
        // Mean clock period (ticks) over the frame's rises; the previous frame's until
        // there are two. Kept up to date wherever the rises change (updatePeriod()).
        double period = 0;
        // The lines' levels, 0 or 1, as words: sl is shifted into `data` as it is.
        std::uint64_t ma = 1, sl = 1;
        int data_count = 0;
        Slot slot = Slot::Ack;
    };
    // What takeDataEdge() needs beside RunFields, none of it state of its own: the rises'
    // storage, with room reserved, and their count, a local for a run (dataRun() sets it
    // back) or the list's own for one edge (Count = std::size_t&); two values derived
    // from RunFields, kept up to date rather than worked out at every edge; and the quiet
    // limit, read once.
    template <class Count>
    struct RunRoom {
        Tick* rises;
        Count nrises;
        double gaps;         // nrises - 1: the period's divisor (periodOver())
        double half_period;  // period / 2.0, as sampleAt() adds it
        Tick quiet_ticks;
    };
    template <class Count>
    RunRoom<Count> runRoom() {
        return {f_.rises.data(), Count(f_.rises.sizeRef()), double(f_.rises.size() - 1),
                run_.period / 2.0, c_.quiet_ticks};
    }
    // The rest of a frame: plain fields (compared whole by spliceState()), its rises and
    // its errors.
    struct FrameFields {
        Tick start = 0;
        Tick ma_still = 0;         // MA unchanged this long before start
        bool from_hold = false;    // started from MA low (Hold-CDM)
        Tick hold_fall = kNoTick;  // first MA fall after a start from MA low
        Tick ack = kNoTick;
        double ack_delay = 0;  // 2nd MA rising edge -> ACK, as measured
        int proc_cycles = 0;
        int start_index = -1;  // rise index of the start bit
        int stop_index = -1;
        int cds = -1;
        int ne = -1, nw = -1;
        std::uint32_t crc_rx = 0;
        int crc_count = 0;
        Tick timeout_end = kNoTick;  // SL rising edge ending the slave's timeout
        bool ma_at_timeout_end = true;
        // The slave timed out while the master was still clocking past the stop bit, and
        // took the remaining clocks for a new request (the MB5U with a RESOLUTE does this).
        bool retriggered = false;
    };
    struct Frame : FrameFields {
        RiseList rises;  // MA rising edges; rises[0] = LAT
        std::vector<std::string> errors;
    };

    // Every clocked slot so far sampled and taken: the frame can close without losing one.
    bool clockedSamplesTaken() const {
        return run_.scheduled == f_.rises.size() && sampler_.pending() == 0;
    }
    // Only in State::Data with the sampler empty (and two rises, a period, seen).
    bool dataEdgesNow() const {
        return c_.state == State::Data && sampler_.empty() && f_.rises.size() >= 2;
    }
    // One usual edge of a frame's data (dataEdgesNow()): what the general path (onMa(),
    // onSl()) does with it, the same arithmetic in the same order, so that every sample
    // time and delay comes out bit for bit the same, but with the samples taken as they
    // fall due instead of through the LineSampler's buffer. False for any other edge
    // (a clock pause, a sample pushed past its edge, a high ACK, the stop bit, an SL
    // change after a sample due): the samples due before it that it could take are
    // taken, and the general path goes on from there (after dataRun() stores its locals).
    // `key`: edgeKey().
    template <class Count>
    [[gnu::always_inline]] inline bool takeDataEdge(RunFields& s, RunRoom<Count>& r, Tick t,
                                                    unsigned key);
    // takeDataEdge()'s key: role * 2 + level, the low byte of an Edge whose line is its
    // role (FastPathHints::lines_are_roles); beyond kSl * 2 + 1 for any other role.
    static unsigned edgeKey(int role, bool level) { return unsigned(role) * 2u + unsigned(level); }
    template <bool kLevel, class Count>
    [[gnu::always_inline]] inline bool takeMaEdge(RunFields& s, RunRoom<Count>& r, Tick t);
    template <class Count>
    [[gnu::always_inline]] inline bool takeSlEdge(RunFields& s, RunRoom<Count>& r, Tick t,
                                                  bool level);
    // Before the ACK (State::WaitAck) with the sampler empty: an MA edge that onMa() would
    // only record (a clock phase, a rise), taken without the sampler and the state switch:
    // three edges of a usual frame. False for any other edge (an SL edge, a pause that
    // checkQuiet() acts on), which the general path takes.
    [[gnu::always_inline]] inline bool takeAckWaitEdge(Tick t, int role, bool level);
    // What an MA edge before the ACK does to the frame, once recorded (recordMaEdge()): a
    // rise is a clock, a fall after a first rise from low may end Hold-CDM's LAT phase.
    void clockBeforeAck(Tick t, bool level) {
        if (level)
            addRise(t);
        else if (f_.from_hold && f_.rises.size() == 1)
            f_.hold_fall = t;
    }
    // Takes the edges from `first` on through takeDataEdge(), the state in locals;
    // returns the first edge it did not take. kLinesAreRoles: the role is the edge's line
    // (FastPathHints::lines_are_roles), not looked up.
    // Out of line, as it was before it became a template: the function perf names, and
    // the code the micro-benchmarks measure.
    static constexpr std::ptrdiff_t kMaxRun = 1024;  // edges a run takes at most (edges())
    template <bool kLinesAreRoles>
    [[gnu::noinline]] const Edge* dataRun(const Edge* first, const Edge* last,
                                          const int* role_of_line);
    void onMa(Tick t, bool level);
    void onMaAfterSamples(Tick t, bool level);  // onMa() once the due samples are taken
    // MA at `level` from tick t on; in_frame: the phase it ends was a clock phase of the
    // frame, and counts towards its longest (masterGaveUp() before the ACK,
    // isClockPhase() from it on).
    [[gnu::always_inline]] void recordMaEdge(Tick t, bool level, bool in_frame) {
        recordMaEdgeOf(run_, t, level, in_frame);
    }
    // recordMaEdge()'s work on the state given (the member, or a run's local copy). A
    // branch on the level, not a reference chosen by it: a local whose field had its
    // address taken would live in memory, not in registers.
    [[gnu::always_inline]] static void recordMaEdgeOf(RunFields& s, Tick t, bool level,
                                                      bool in_frame) {
        if (in_frame) {
            if (level)
                s.max_low = std::max(s.max_low, t - s.last_ma_edge);
            else
                s.max_high = std::max(s.max_high, t - s.last_ma_edge);
        }
        s.last_ma_edge = t;
        s.ma = level;
    }
    void onSl(Tick t, bool level);
    // ma_still: how long MA had not changed before `start` (from the capture's start for
    // its first edge).
    void beginFrame(Tick start, bool from_hold, Tick ma_still);
    // For a frame before any trusted start: did it begin after MA was idle (not inside a
    // frame the capture started in)?
    bool startedFromIdle() const;
    // Per-edge helpers of the general path (sampleTime is defined below the class,
    // scheduleUpTo and drainSamples in bissc_decoder.cpp).
    [[gnu::always_inline]] inline double sampleTime(std::size_t k) const;
    // Slot k's sample time with this line delay and mean period (sampleTime()).
    [[gnu::always_inline]] double sampleTimeWith(std::size_t k, double delay, double period) const {
        return sampleAt(f_.rises[k], delay, period / 2.0);
    }
    // The sample time of the slot driven after `rise`: the same sum in the same order on
    // every path, so that the samples come out bit for bit the same.
    [[gnu::always_inline]] static double sampleAt(Tick rise, double delay, double half_period) {
        return double(rise) + delay + half_period;
    }
    [[gnu::always_inline]] inline void scheduleUpTo(double t);
    void startDelayEstimate(double ack_delay);
    void refineDelay(Tick t);
    // refineDelay()'s work on the state given (the member, or a run's local copy): an SL
    // edge `offset` ticks after the rise it answers.
    [[gnu::always_inline]] static inline void refineDelayOf(RunFields& s, double offset,
                                                            double half_period);
    [[gnu::always_inline]] inline void drainSamples();
    void takeSample(int index, bool level, double t);
    // The samples that only set a field of the frame and move `slot` on: a low ACK, the
    // busy slots, CDS, nE, nW and the CRC. False, having changed nothing, for the others
    // (data bits, a high ACK, the stop bit), which takeSample() handles itself.
    [[gnu::always_inline]] bool takePlainSlot(Slot& slot, int index, bool level) {
        switch (slot) {
            case Slot::Ack:
                if (level) return false;  // an error to add
                slot = Slot::Busy;
                return true;
            case Slot::Busy:
                if (!level) {
                    ++f_.proc_cycles;
                } else {
                    f_.start_index = index;
                    slot = Slot::Cds;
                }
                return true;
            case Slot::Cds:
                f_.cds = level;
                slot = s_.bits > 0 ? Slot::Data : Slot::NE;
                return true;
            case Slot::NE:
                f_.ne = level;
                slot = Slot::NW;
                return true;
            case Slot::NW:
                f_.nw = level;
                slot = s_.crc_bits > 0 ? Slot::Crc : Slot::Stop;
                return true;
            case Slot::Crc:
                f_.crc_rx = (f_.crc_rx << 1) | std::uint32_t(level);
                if (++f_.crc_count == s_.crc_bits) slot = Slot::Stop;
                return true;
            default:
                return false;
        }
    }
    // A position bit (Slot::Data), the bulk of a frame's samples.
    [[gnu::always_inline]] void takeDataBit(bool level) { takeDataBitOf(run_, level); }
    [[gnu::always_inline]] void takeDataBitOf(RunFields& s, std::uint64_t level) const {
        s.data = (s.data << 1) | level;
        if (++s.data_count == s_.bits) s.slot = Slot::NE;
    }
    // Ticks, over the frame's rising edges so far. Asked several times per edge, worked
    // out once per rising edge.
    double meanPeriod() const { return run_.period; }
    [[gnu::always_inline]] void updatePeriod() {
        run_.period = f_.rises.size() < 2 ? c_.last_period : periodOfRises();
    }
    // The mean period over rises[] (two or more).
    [[gnu::always_inline]] double periodOfRises() const {
        const auto& r = f_.rises;
        return periodOver(r.front(), r.back(), double(r.size() - 1));
    }
    // The mean period from the first rise to the last, `gaps` periods apart: the one
    // formula of the general path (periodOfRises()) and the runs (takeMaEdge()), so that
    // both give the same period bit for bit.
    [[gnu::always_inline]] static double periodOver(Tick first, Tick last, double gaps) {
        return double(last - first) / gaps;
    }
    // A rising MA edge of the frame, on the general path (takeMaEdge() appends its rises
    // from its own state, through periodOver() too).
    [[gnu::always_inline]] void addRise(Tick t) {
        f_.rises.push_back(t);
        updatePeriod();
    }
    double quietLimit() const;  // MA silence (ticks) that ends a frame in progress
    // Emits the frame in progress. timeout_end = the SL rising edge ending the slave's
    // timeout, or kNoTick; feed_control passes its CDM/CDS bits on to the reassembler.
    void closeFrame(Tick end, Tick timeout_end, const char* error, bool feed_control);
    // closeFrame()'s steps: what the frame came to (its faults added to `e`), its fields,
    // its summary, and the running totals.
    struct FrameOutcome {
        bool complete = false, crc_good = true, timed_out = false, acked = false;
        bool clocked = false;
        std::uint64_t pos = 0;
        int cdm = -1;
        std::int64_t timeout_ns = 0, delay_ns = 0;
        double period = 0;
    };
    FrameOutcome checkFrame(Event& e, Tick timeout_end);
    void addFrameFields(Event& e, const FrameOutcome& out) const;
    void setFrameSummary(Event& e, const FrameOutcome& out) const;
    void countFrame(const Event& e, const FrameOutcome& out);
    void addError(const std::string& e);
    // Closes a frame whose clock went quiet. Called on every edge: the inline part only
    // rules out the usual case (clock running, well within kMinQuietNs and, before the
    // ACK, within masterGaveUp()'s pause).
    void checkQuiet(Tick now) {
        if (quietMayEnd(now)) checkQuietSlow(now);
    }
    // checkQuiet()'s inline test: false in the usual case, where checkQuietSlow() would
    // do nothing (takeAckWaitEdge() asks it too).
    bool quietMayEnd(Tick now) const {
        return c_.state == State::TimeoutEnded ||
               ((c_.state == State::WaitAck || c_.state == State::Data) &&
                run_.last_ma_edge != kNoTick &&
                (now - run_.last_ma_edge > c_.quiet_ticks ||
                 (c_.state == State::WaitAck && masterGaveUp(now))));
    }
    // In WaitAck: has MA stayed high for many of the frame's clock phases (or, none
    // seen yet, of the previous frame's)? Until the ACK the master clocks without a
    // break, so such a pause is the master giving up on a slave that did not answer,
    // however short of kMinQuietNs: frames closer together than that would otherwise
    // run into one. MA risen from low and staying high is a return to idle instead
    // (checkQuietSlow()). Neither phase known (a first frame, only LAT seen): the rule
    // of quietLimit() decides alone.
    bool masterGaveUp(Tick now) const {
        if (!run_.ma || (f_.from_hold && f_.rises.size() == 1)) return false;
        const Tick phase = std::max(run_.max_high, run_.max_low);
        const double limit = kGaveUpPhases * (phase > 0 ? double(phase) : c_.last_period / 2);
        return limit > 0 && double(now - run_.last_ma_edge) > limit;
    }
    // MA high this many of the frame's longest clock phases before the ACK: the master
    // gave up. Far above a clock's jitter or an uneven duty cycle, far below the pause
    // between frames, which is at least the slave's timeout.
    static constexpr double kGaveUpPhases = 8.0;
    // c_.quiet_ticks for c_.min_quiet and c_.slave_timeout as they are now.
    void updateQuietTicks();
    void checkQuietSlow(Tick now);
    void resolveHoldStart(Tick ack);
    // Could an MA phase of this length (ending with an edge to `level`) be a clock phase?
    bool isClockPhase(double length, bool level) const;

    BisscSettings s_;
    FixedLengthCrc crc_;  // the frame CRC, over the data bits, nE and nW
    BisscControlReassembler control_;
    LineSampler sampler_;
    // The decoder's own state beside the frame's: compared whole when splicing
    // (spliceState()), so a field added here cannot be left out of the comparison.
    struct Carried {
        State state = State::Idle;
        double last_delay = -1;  // line delay of the previous frame (ticks), -1 unknown
        bool glitch_pending = false;
        double last_period = 0;  // mean clock period of the previous frame (ticks)
        double min_quiet = 0;    // kMinQuietNs in ticks
        // The slave's timeout (ticks, last rising MA edge to SL rising, as seen at the
        // master) measured on the last frame that ran into it; infinite until then.
        double slave_timeout = std::numeric_limits<double>::infinity();
        // floor(min(min_quiet, slave_timeout)): no more than quietLimit() (the line delay is
        // never negative: it is measured from an MA rise to a later SL edge), so a gap of
        // whole ticks n can only end a frame if n > quiet_ticks: checkQuiet()'s test per
        // edge, without a conversion; checkQuietSlow() decides. It does not follow the
        // delay, so that refining the delay on every SL edge need not work it out again.
        Tick quiet_ticks = 0;
        // A frame has begun after MA idle: until then a frame may be the rest of one the
        // capture started inside, and is skipped unless it shows MA idle before it.
        bool frame_start_seen = false;
    };
    Carried c_;
    RunFields run_;
    Frame f_;
    std::uint64_t frames_ = 0, answered_frames_ = 0, clean_frames_ = 0;
    // Edges outside a frame's data (onMa, onSl, takeAckWaitEdge()): all of them while no
    // frame is running.
    std::uint64_t slow_ma_edges_ = 0, slow_sl_edges_ = 0;
    std::uint64_t skipped_frames_ = 0;  // before the first frame start to trust
    Tick capture_start_ = 0;
};

inline void BisscDecoder::updateQuietTicks() {
    // floor() by truncation and one correction; clamped, so that a timeout measured
    // across an absurd gap cannot overflow.
    constexpr double kMaxTick = 9.0e18;
    const double limit = std::clamp(std::min(c_.min_quiet, c_.slave_timeout), -kMaxTick, kMaxTick);
    Tick q = Tick(limit);
    if (double(q) > limit) --q;
    c_.quiet_ticks = q;
}

inline void BisscDecoder::refineDelay(Tick t) {
    // Every SL change in the frame is the slave answering an MA rising edge: the one
    // whose slot has not been sampled yet (all samples before t are scheduled, the next
    // slot's is after t).
    if (run_.scheduled < f_.rises.size())
        refineDelayOf(run_, double(t - f_.rises[run_.scheduled]), meanPeriod() / 2.0);
}

inline void BisscDecoder::refineDelayOf(RunFields& s, double offset, double half_period) {
    // The offset is one more measurement of the line delay; the mean resolves the delay
    // to a fraction of a capture sample (the ACK edge alone is quantised to a whole
    // sample, 0.4 bit at 2.4 samples per bit).
    if (s.period <= 0) return;
    if (std::fabs(offset - s.delay) >= half_period) return;
    s.delay_sum += offset;
    ++s.delay_edges;
    s.delay = s.delay_sum / s.delay_edges;
}

double BisscDecoder::sampleTime(std::size_t k) const {
    // Slot k (k >= 1; 1 = ACK) is driven after rising edge k and valid from r_k + d to
    // r_{k+1} + d: sample its middle. T is the frame's mean period, which smooths the
    // quantisation of a capture sampled at only a few samples per bit.
    return sampleTimeWith(k, run_.delay, meanPeriod());
}

std::shared_ptr<const DecoderFactory> makeBisscFactory();

}  // namespace busdecode
