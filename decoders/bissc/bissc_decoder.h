#pragma once
// BiSS-C (continuous mode, point to point) from the master clock MA and the slave line
// SL, as seen at the master. Per frame (PROTOCOLS.md §1.1):
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
#include "core/crc.h"
#include "core/decoder.h"
#include "core/line_sampler.h"
#include "core/registry.h"

namespace busdecode {

class BisscDecoder : public BlockDecoder<BisscDecoder> {
public:
    enum Role { kMa = 0, kSl = 1 };

    explicit BisscDecoder(const Options& options);

    void start(const DecoderContext& ctx) override;
    // Inline, with its fast paths, so that BlockDecoder's loop takes the usual MA and SL
    // edges without a call (defined below the class).
    [[gnu::always_inline]] inline void edge(Tick t, int role, bool level) override;
    void advance(Tick now) override;
    void finish(Tick end) override;
    void glitch(Tick t, int role) override;
    Tick watermark(Tick now) const override;
    // Advice when fewer than one in eight answered frames came out clean (see
    // cleanFrames()): the data width, the CRC options or the mapping is the likely cause;
    // or when the lines change but no frame is answered: the mapping.
    std::vector<std::string> advice() const override;

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

    struct Frame {
        Tick start = 0;
        bool from_hold = false;    // started from MA low (Hold-CDM)
        Tick hold_fall = kNoTick;  // first MA fall after a start from MA low
        std::vector<Tick> rises;   // MA rising edges; rises[0] = LAT
        Tick ack = kNoTick;
        double delay = 0;      // line delay in ticks: mean over the SL edges so far
        double ack_delay = 0;  // 2nd MA rising edge -> ACK, as measured
        double delay_sum = 0;
        int delay_edges = 0;
        std::size_t scheduled = 1;  // rises with a scheduled sample (index 0 = LAT has none)
        double last_sample_t = -1e300;
        Slot slot = Slot::Ack;
        int proc_cycles = 0;
        int start_index = -1;  // rise index of the start bit
        int stop_index = -1;
        int cds = -1;
        std::uint64_t data = 0;
        int data_count = 0;
        int ne = -1, nw = -1;
        std::uint32_t crc_rx = 0;
        int crc_count = 0;
        Tick timeout_end = kNoTick;  // SL rising edge ending the slave's timeout
        bool ma_at_timeout_end = true;
        // The slave timed out while the master was still clocking past the stop bit, and
        // took the remaining clocks for a new request (the MB5U with a RESOLUTE does this).
        bool retriggered = false;
        Tick max_high = 0, max_low = 0;  // longest MA clock phases seen in the frame (ticks)
        // Mean clock period (ticks) over `rises`; the previous frame's until there are
        // two. Kept up to date wherever `rises` changes (updatePeriod()).
        double period = 0;
        std::vector<std::string> errors;
    };

    void onMa(Tick t, bool level);
    // The usual MA edge: inside a frame's data, clock running, the samples due before it
    // taken at once. Does all of onMa()'s work for it and returns true; false for every
    // other edge, and onMa() handles it (from the first sample not taken yet).
    [[gnu::always_inline]] inline bool onMaInFrame(Tick t, bool level);
    void onMaAfterSamples(Tick t, bool level);  // onMa() once the due samples are taken
    // MA at `level` from tick t on; in_frame: the phase it ends was a clock phase of the
    // frame, and counts towards its longest (isClockPhase()).
    [[gnu::always_inline]] void recordMaEdge(Tick t, bool level, bool in_frame) {
        if (in_frame) {
            Tick& longest = level ? f_.max_low : f_.max_high;
            longest = std::max(longest, t - last_ma_edge_);
        }
        last_ma_edge_ = t;
        ma_ = level;
    }
    void onSl(Tick t, bool level);
    // The usual SL edge: inside a frame's data, clock running, the sampler empty and the
    // next sample still to come. Does all of onSl()'s work for it (refining the line
    // delay) and returns true; false, having changed nothing, for every other edge.
    [[gnu::always_inline]] inline bool onSlInFrame(Tick t, bool level);
    void beginFrame(Tick start, bool from_hold);
    // Per-edge helpers, inlined into edge/onMa/onSl (sampleTime and takeDueSamples are
    // defined below the class, scheduleUpTo and drainSamples in bissc_decoder.cpp).
    [[gnu::always_inline]] inline double sampleTime(std::size_t k) const;
    [[gnu::always_inline]] inline void scheduleUpTo(double t);
    // The usual MA edge's samples without the sampler's buffer; false: use the general
    // path (scheduleUpTo, LineSampler::advanceTo, drainSamples).
    [[gnu::always_inline]] inline bool takeDueSamples(Tick t);
    void startDelayEstimate(double ack_delay);
    void refineDelay(Tick t);
    [[gnu::always_inline]] inline void drainSamples();
    void takeSample(int index, bool level, double t);
    // A position bit (Slot::Data), the bulk of a frame's samples.
    [[gnu::always_inline]] void takeDataBit(bool level) {
        f_.data = (f_.data << 1) | std::uint64_t(level);
        if (++f_.data_count == s_.bits) f_.slot = Slot::NE;
    }
    // Ticks, over the frame's rising edges so far. Asked several times per edge, worked
    // out once per rising edge.
    double meanPeriod() const { return f_.period; }
    [[gnu::always_inline]] void updatePeriod() {
        const auto& r = f_.rises;
        f_.period =
            r.size() < 2 ? last_period_ : double(r.back() - r.front()) / double(r.size() - 1);
    }
    // A rising MA edge of the frame. (Inlined by force, as the helpers above: GCC's own
    // choice moved it out of the block loop when the class grew, 4 % more instructions.)
    [[gnu::always_inline]] void addRise(Tick t) {
        f_.rises.push_back(t);
        updatePeriod();
    }
    double quietLimit() const;  // MA silence (ticks) that ends a frame in progress
    // Emits the frame in progress. timeout_end = the SL rising edge ending the slave's
    // timeout, or kNoTick; feed_control passes its CDM/CDS bits on to the reassembler.
    void closeFrame(Tick end, Tick timeout_end, const char* error, bool feed_control);
    void addError(const std::string& e);
    // Closes a frame whose clock went quiet. Called on every edge: the inline part only
    // rules out the usual case (clock running, well within kMinQuietNs).
    void checkQuiet(Tick now) {
        if (state_ == State::TimeoutEnded ||
            ((state_ == State::WaitAck || state_ == State::Data) && last_ma_edge_ != kNoTick &&
             now - last_ma_edge_ > quiet_ticks_))
            checkQuietSlow(now);
    }
    // The frame's line delay changed: f_.delay and the quiet threshold that depends on it.
    void setDelay(double delay);
    void checkQuietSlow(Tick now);
    void resolveHoldStart(Tick ack);
    // Could an MA phase of this length (ending with an edge to `level`) be a clock phase?
    bool isClockPhase(double length, bool level) const;

    BisscSettings s_;
    BitCrc crc_;  // the frame CRC's polynomial and table, reset for every frame
    BisscControlReassembler control_;
    LineSampler sampler_;
    State state_ = State::Idle;
    Frame f_;
    bool ma_ = true, sl_ = true;
    Tick last_ma_edge_ = kNoTick;
    double last_delay_ = -1;  // line delay of the previous frame (ticks), -1 unknown
    bool glitch_pending_ = false;
    double last_period_ = 0;  // mean clock period of the previous frame (ticks)
    double min_quiet_ = 0;    // kMinQuietNs in ticks
    // The slave's timeout (ticks, last rising MA edge to SL rising, as seen at the master)
    // measured on the last frame that ran into it; infinite until then.
    double slave_timeout_ = std::numeric_limits<double>::infinity();
    // floor(min(min_quiet_ + f_.delay, slave_timeout_)): for whole ticks n, n > it exactly
    // when double(n) is above that, without a conversion per edge.
    Tick quiet_ticks_ = 0;
    std::uint64_t frames_ = 0, answered_frames_ = 0, clean_frames_ = 0;
    // Edges that took the slow paths (onMa, onSl): all of them while no frame is running.
    std::uint64_t slow_ma_edges_ = 0, slow_sl_edges_ = 0;
};

void BisscDecoder::edge(Tick t, int role, bool level) {
    if (role == kMa) {
        if (!onMaInFrame(t, level)) onMa(t, level);
    } else if (role == kSl) {
        if (!onSlInFrame(t, level)) onSl(t, level);
    }
}

bool BisscDecoder::onMaInFrame(Tick t, bool level) {
    // onMa() for an edge that finds the frame's data being clocked and no quiet gap
    // before it: once takeDueSamples() has taken the samples due, checkQuiet() has
    // nothing to do, and only the phase length, the level and a rise are left to record.
    if (state_ != State::Data || t - last_ma_edge_ > quiet_ticks_ || !takeDueSamples(t))
        return false;
    if (state_ != State::Data) {  // the stop bit ended the data: onMa() goes on
        onMaAfterSamples(t, level);
        return true;
    }
    recordMaEdge(t, level, true);
    if (level) addRise(t);  // its sample is scheduled when due
    return true;
}

bool BisscDecoder::takeDueSamples(Tick t) {
    // What scheduleUpTo + advanceTo + drainSamples do at an MA edge when the sampler is
    // empty: every sample due before t resolves to SL's level now (the sampler gives a
    // newly scheduled sample the line's present level), and is taken at once, in order.
    // Not at an SL edge: there the samples are taken after SL's new level is recorded.
    if (state_ != State::Data || !sampler_.empty()) return false;
    const double now = double(t);
    while (state_ == State::Data && f_.scheduled < f_.rises.size()) {
        double at = sampleTime(f_.scheduled);
        if (at >= now) break;
        at = std::max(at, f_.last_sample_t);
        if (at >= now) return false;  // pushed to t or later: it waits in the sampler
        f_.last_sample_t = at;
        const std::size_t k = f_.scheduled++;
        if (f_.slot == Slot::Data)
            takeDataBit(sampler_.level());  // what takeSample() does with it, without a call
        else
            takeSample(int(k), sampler_.level(), at);
    }
    return true;
}

bool BisscDecoder::onSlInFrame(Tick t, bool level) {
    // Then scheduleUpTo(), lineEdge() and drainSamples() have nothing to resolve or take,
    // and checkQuiet() nothing to close.
    if (state_ != State::Data || t - last_ma_edge_ > quiet_ticks_ || !sampler_.empty())
        return false;
    // The usual SL edge answers a rise whose sample is still to come: with every sample
    // taken, the edge may be the slave giving up (onSl() checks).
    if (f_.scheduled >= f_.rises.size() || sampleTime(f_.scheduled) < double(t)) return false;
    sampler_.lineEdge(t, level);  // nothing to resolve: only the level
    sl_ = level;
    refineDelay(t);  // (the slot is never Done in State::Data)
    return true;
}

inline void BisscDecoder::setDelay(double delay) {
    f_.delay = delay;
    // floor() by truncation and one correction (std::floor is a library call without
    // SSE4.1); clamped, so that a delay measured across an absurd gap cannot overflow.
    constexpr double kMaxTick = 9.0e18;
    const double limit =
        std::clamp(std::min(min_quiet_ + delay, slave_timeout_), -kMaxTick, kMaxTick);
    Tick q = Tick(limit);
    if (double(q) > limit) --q;
    quiet_ticks_ = q;
}

inline void BisscDecoder::refineDelay(Tick t) {
    // Every SL change in the frame is the slave answering an MA rising edge: the one
    // whose slot has not been sampled yet (all samples before t are scheduled, the next
    // slot's is after t). Its offset is one more measurement of the line delay; the mean
    // resolves the delay to a fraction of a capture sample (the ACK edge alone is
    // quantised to a whole sample, 0.4 bit at 2.4 samples per bit).
    const double period = meanPeriod();
    if (period <= 0 || f_.scheduled >= f_.rises.size()) return;
    const double offset = double(t - f_.rises[f_.scheduled]);
    if (std::fabs(offset - f_.delay) >= period / 2) return;
    f_.delay_sum += offset;
    ++f_.delay_edges;
    setDelay(f_.delay_sum / f_.delay_edges);
}

double BisscDecoder::sampleTime(std::size_t k) const {
    // Slot k (k >= 1; 1 = ACK) is driven after rising edge k and valid from r_k + d to
    // r_{k+1} + d: sample its middle. T is the frame's mean period, which smooths the
    // quantisation of a capture sampled at only a few samples per bit.
    return double(f_.rises[k]) + f_.delay + meanPeriod() / 2.0;
}

std::shared_ptr<const DecoderFactory> makeBisscFactory();

}  // namespace busdecode
