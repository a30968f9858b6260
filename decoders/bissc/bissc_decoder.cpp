#include "bissc_decoder.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "core/bit_word.h"
#include "core/crc.h"
#include "core/number_text.h"

namespace busdecode {

namespace {

// A rising MA edge from low, followed by a high phase this many times longer than the
// low phase after it, was the master returning to idle (CDM = 1 without Hold-CDM); a
// shorter one was the LAT of a Hold-CDM frame.
constexpr double kIdleReturnRatio = 3.0;
// An SL change this many bit periods after the last clocked slot is not a data bit.
constexpr double kLateSlEdgePeriods = 1.5;
// A clock pause longer than this ends a frame in progress (C6: clock phases <= 12.5 us).
constexpr double kMinQuietNs = 20000.0;
// Before the first frame start known to be one: MA still this many times the frame's
// longest clock phase before it began was idle, not clocking in a frame the capture
// started inside (which may show a low and a high phase as one: a VCD line reads 1 from
// the capture's start until its first change).
constexpr double kStartIdlePhases = 2.5;

}  // namespace

BisscDecoder::BisscDecoder(const Options& options)
    : FastDecoder("bissc"),
      s_(BisscSettings::from(options)),
      crc_(BitCrc::fromFullPoly(s_.crc_poly, s_.crc_init, s_.crc_inverted), s_.bits + 2),
      control_([this](Event&& e) { emit(std::move(e)); }) {}

void BisscDecoder::start(const DecoderContext& ctx) {
    Decoder::start(ctx);
    c_.min_quiet = tb().fromNs(kMinQuietNs);
    run_.delay = 0;
    updateQuietTicks();
    run_.ma = ctx.initial_levels.size() > kMa ? ctx.initial_levels[kMa] != 0 : true;
    run_.sl = ctx.initial_levels.size() > kSl ? ctx.initial_levels[kSl] != 0 : true;
    sampler_.reset(run_.sl);
    capture_start_ = ctx.capture_start;
    // A capture that starts with SL low starts inside a frame or a timeout.
    c_.state = run_.sl ? State::Idle : State::WaitSlaveIdle;
}

Tick BisscDecoder::watermark(Tick now) const {
    Tick w = Decoder::watermark(now);
    const Tick c = control_.openSince();
    if (c != kNoTick) w = std::min(w, c);
    return w;
}

void BisscDecoder::advance(Tick now) {
    scheduleUpTo(double(now));
    sampler_.advanceTo(now);
    drainSamples();
    checkQuiet(now);
}

void BisscDecoder::glitch(Tick t, int role) {
    (void)t;
    (void)role;
    if (c_.state == State::WaitAck || c_.state == State::Data || c_.state == State::Timeout ||
        c_.state == State::TimeoutEnded)
        addError("glitch");
    else
        c_.glitch_pending = true;
}

void BisscDecoder::addError(const std::string& e) {
    if (std::find(f_.errors.begin(), f_.errors.end(), e) == f_.errors.end()) f_.errors.push_back(e);
}

double BisscDecoder::quietLimit() const {
    // Or the slave's timeout as seen before: a clock paused that long has reset the slave
    // (its next clocks are a new request, even if the pause was short of kMinQuietNs).
    return std::min(std::max(c_.min_quiet, 3.0 * meanPeriod()) + run_.delay, c_.slave_timeout);
}

void BisscDecoder::checkQuietSlow(Tick now) {
    if (c_.state == State::TimeoutEnded) {
        // The clock did not go on within a clock phase of its last edge: frame over.
        if (!isClockPhase(double(now - run_.last_ma_edge), !run_.ma) && now >= f_.timeout_end) {
            // After clocks past an early slave timeout, CDM is where the master left MA.
            if (f_.retriggered) f_.ma_at_timeout_end = run_.ma;
            closeFrame(f_.timeout_end, f_.timeout_end, nullptr, true);
            c_.state = run_.sl ? State::Idle : State::WaitSlaveIdle;
        }
        return;
    }
    // checkQuiet() only calls this in WaitAck / Data with a clock edge seen. The frame
    // ends once the clock has been quiet past quietLimit() or, before the ACK, once the
    // master gave up (never for a lone rise from low: that case is next).
    if (double(now - run_.last_ma_edge) <= quietLimit() &&
        !(c_.state == State::WaitAck && masterGaveUp(now)))
        return;
    // A clocked slot's sample still ahead (a learnt timeout shorter than the line delay and
    // half a period): close once it is taken, so that where the quiet is noticed (an edge,
    // a piece's end) cannot change the frame.
    if (c_.state == State::Data && !clockedSamplesTaken()) return;
    if (c_.state == State::WaitAck && f_.from_hold && f_.rises.size() == 1) {
        // MA rose from low and stayed high: the master went back to idle after CDM = 1.
        c_.state = State::Idle;
        idle();
        return;
    }
    const char* why = c_.state == State::WaitAck ? "no_ack"
                      : run_.slot == Slot::Busy  ? "no_start"
                                                 : "short_frame";
    closeFrame(run_.last_ma_edge, kNoTick, why, true);
    c_.state = run_.sl ? State::Idle : State::WaitSlaveIdle;
}

bool BisscDecoder::isClockPhase(double length, bool level) const {
    // A rising edge ends a low phase. BiSS keeps clock phases well below the slave's
    // timeout, so a phase much longer than any in the frame is not clocking.
    constexpr double kPhaseTolerance = 1.25;
    const double longest = double(level ? run_.max_low : run_.max_high);
    return longest > 0 && length <= kPhaseTolerance * longest;
}

void BisscDecoder::resolveHoldStart(Tick ack) {
    // A frame that began with MA rising from low is either a Hold-CDM frame (that rise
    // was LAT) or the master's return to idle after CDM = 1 followed by a normal frame
    // (LAT is the rise after the next fall). The ACK follows the 2nd LAT-counted rise by
    // the line delay: pick the reading whose delay matches the previous frame's, or, for
    // a first frame, the one whose first high phase looks like a clock phase.
    if (!f_.from_hold || f_.hold_fall == kNoTick || f_.rises.size() < 3 || ack < f_.rises[2])
        return;
    const double as_hold = double(ack - f_.rises[1]);
    const double as_idle = double(ack - f_.rises[2]);
    bool idle_return;
    if (c_.last_delay >= 0) {
        idle_return = std::fabs(as_idle - c_.last_delay) < std::fabs(as_hold - c_.last_delay);
    } else {
        const double high = double(f_.hold_fall - f_.rises[0]);
        const double low = double(f_.rises[1] - f_.hold_fall);
        idle_return = high > kIdleReturnRatio * low;
    }
    if (!idle_return) return;
    f_.ma_still = std::max(f_.ma_still, f_.hold_fall - f_.rises[0]);
    f_.rises.eraseFirst();
    updatePeriod();  // the first rise changed
    f_.start = f_.hold_fall;
    f_.from_hold = false;
    setBusyFrom(f_.start);
}

void BisscDecoder::beginFrame(Tick start, bool from_hold, Tick ma_still) {
    // A fresh frame, keeping the vectors' storage (one frame every few microseconds).
    RiseList rises = std::move(f_.rises);
    std::vector<std::string> errors = std::move(f_.errors);
    rises.clear();
    errors.clear();
    f_ = Frame{};
    f_.rises = std::move(rises);
    f_.errors = std::move(errors);
    run_ = RunFields{.last_ma_edge = run_.last_ma_edge, .ma = run_.ma, .sl = run_.sl};
    updatePeriod();  // no rises yet: the previous frame's period
    f_.start = start;
    f_.from_hold = from_hold;
    f_.ma_still = ma_still;
    // MA still past any clock pause: the master was idle, a frame start to trust.
    if (double(ma_still) > c_.min_quiet) c_.frame_start_seen = true;
    sampler_.reset(run_.sl);
    c_.state = State::WaitAck;
    setBusyFrom(start);
    if (c_.glitch_pending) {
        addError("glitch");
        c_.glitch_pending = false;
    }
}

void BisscDecoder::edge(Tick t, int role, bool level) {
    if (dataEdgesNow()) {
        f_.rises.reserve(f_.rises.size() + 1);
        RunRoom<std::size_t&> room = runRoom<std::size_t&>();
        if (takeDataEdge(run_, room, t, edgeKey(role, level))) {
            if (role == kSl) sampler_.setLevel(level);  // (empty)
            return;
        }
    }
    if (!takeAckWaitEdge(t, role, level)) edgeReference(t, role, level);
}

void BisscDecoder::edges(const Edge* first, const Edge* last, const int* role_of_line) {
    while (first != last) {
        // A frame's data is most of the edges: taken in runs, each ended by the first
        // edge that needs more than the usual (takeDataEdge()), which the general path
        // then takes.
        if (dataEdgesNow()) {
            // At most kMaxRun edges a run: the room it reserves for its rises stays small
            // (a decoder started for each piece of a file, piece_speculation.h, would
            // otherwise clear and fault in a block's worth, 128 KiB, each).
            const Edge* end = last - first > kMaxRun ? first + kMaxRun : last;
            first = hints().lines_are_roles ? dataRun<true>(first, end, role_of_line)
                                            : dataRun<false>(first, end, role_of_line);
            if (first == last) break;
            if (first == end) continue;  // the run's limit, not an edge it could not take
        }
        const int role = role_of_line[first->line];
        if (!takeAckWaitEdge(first->t, role, first->level != 0))
            edgeReference(first->t, role, first->level != 0);
        ++first;
    }
}

void BisscDecoder::edgeReference(Tick t, int role, bool level) {
    if (role == kMa)
        onMa(t, level);
    else if (role == kSl)
        onSl(t, level);
}

template <class Count>
bool BisscDecoder::takeDataEdge(RunFields& s, RunRoom<Count>& r, Tick t, unsigned key) {
    // One case per role and level, each with its level a constant: no branch on the level
    // after the one on the role.
    switch (key) {
        case kMa * 2 + 0:
            return takeMaEdge<false>(s, r, t);
        case kMa * 2 + 1:
            return takeMaEdge<true>(s, r, t);
        case kSl * 2 + 0:
            return takeSlEdge(s, r, t, false);
        case kSl * 2 + 1:
            return takeSlEdge(s, r, t, true);
        default:
            return false;
    }
}

template <bool kLevel, class Count>
bool BisscDecoder::takeMaEdge(RunFields& s, RunRoom<Count>& r, Tick t) {
    if (t - s.last_ma_edge > r.quiet_ticks) return false;  // a clock pause: checkQuiet()
    // Every sample due before t sees SL's level now (scheduleUpTo() and
    // LineSampler::advanceTo() would resolve it so), taken in order, its time pushed
    // past the last sample's as scheduleUpTo() does.
    const double now = double(t);
    while (s.scheduled < r.nrises) {
        double at = sampleAt(r.rises[s.scheduled], s.delay, r.half_period);
        if (at >= now) break;
        at = std::max(at, s.last_sample_t);
        if (at >= now) return false;  // pushed to t or later: the sampler holds it
        if (s.slot == Slot::Data)
            takeDataBitOf(s, s.sl);
        else if (!takePlainSlot(s.slot, int(s.scheduled), s.sl))
            return false;  // takeSample() takes it
        s.last_sample_t = at;
        ++s.scheduled;
    }
    recordMaEdgeOf(s, t, kLevel, true);
    if constexpr (kLevel) {  // addRise()
        r.rises[r.nrises++] = t;
        r.gaps += 1.0;
        s.period = periodOver(r.rises[0], t, r.gaps);
        r.half_period = s.period / 2.0;
    }
    return true;
}

template <class Count>
bool BisscDecoder::takeSlEdge(RunFields& s, RunRoom<Count>& r, Tick t, bool level) {
    if (t - s.last_ma_edge > r.quiet_ticks) return false;
    // An SL change before the next sample is due answers that sample's rise; otherwise
    // onSl() checks whether the slave gave up.
    if (s.scheduled >= r.nrises ||
        sampleAt(r.rises[s.scheduled], s.delay, r.half_period) < double(t))
        return false;
    s.sl = level;
    refineDelayOf(s, double(t - r.rises[s.scheduled]), r.half_period);
    return true;
}

bool BisscDecoder::takeAckWaitEdge(Tick t, int role, bool level) {
    if (role != kMa || c_.state != State::WaitAck || !sampler_.empty()) return false;
    // onMa() with no sample to take (none is scheduled before the ACK), checkQuiet()
    // finding nothing to do, then onMaAfterSamples()'s WaitAck case.
    if (quietMayEnd(t)) return false;
    ++slow_ma_edges_;
    recordMaEdge(t, level, !f_.rises.empty() && run_.last_ma_edge != kNoTick);
    clockBeforeAck(t, level);
    return true;
}

template <bool kLinesAreRoles>
const Edge* BisscDecoder::dataRun(const Edge* e, const Edge* last, const int* role_of_line) {
    // Room for the rises the run may write: one per edge at most. (Half that if MA's
    // rises and falls alternate, as edges()'s callers promise; the room must not depend
    // on a promise: a rise past it would be written past the storage.)
    f_.rises.reserve(f_.rises.size() + std::size_t(last - e));
    static_assert(splice_detail::kPaddingFree<RunFields>, "RunFields: keep it without padding");
    RunFields s = run_;
    RunRoom<std::size_t> r = runRoom<std::size_t>();
    for (; e != last; ++e) {
        const unsigned key =
            kLinesAreRoles ? e->lineAndLevel() : edgeKey(role_of_line[e->line], e->level != 0);
        if (!takeDataEdge(s, r, e->t, key)) break;
    }
    run_ = s;
    f_.rises.setSize(r.nrises);
    sampler_.setLevel(run_.sl);  // (empty throughout)
    return e;
}

void BisscDecoder::onMa(Tick t, bool level) {
    ++slow_ma_edges_;
    scheduleUpTo(double(t));
    sampler_.advanceTo(t);
    drainSamples();
    onMaAfterSamples(t, level);
}

void BisscDecoder::onMaAfterSamples(Tick t, bool level) {
    checkQuiet(t);
    const Tick still_since = run_.last_ma_edge == kNoTick ? capture_start_ : run_.last_ma_edge;
    recordMaEdge(t, level,
                 (c_.state == State::WaitAck || c_.state == State::Data) && !f_.rises.empty() &&
                     run_.last_ma_edge != kNoTick);

    switch (c_.state) {
        case State::WaitSlaveIdle:
            break;
        case State::Idle:
            if (!level) {
                beginFrame(t, false, t - still_since);
            } else {
                // MA rising from low: maybe LAT (see resolveHoldStart)
                beginFrame(t, true, t - still_since);
                addRise(t);
            }
            break;
        case State::WaitAck:
            clockBeforeAck(t, level);
            break;
        case State::Data:
            if (level) addRise(t);  // its sample is scheduled when due
            break;
        case State::Timeout:
            if (level) addRise(t);  // clocks past the stop bit
            break;
        case State::TimeoutEnded:
            // Still clocking (checkQuiet above closed the frame otherwise): the slave's
            // timeout ended early; these clocks still belong to the master's frame, and
            // the slave may take them for a new request (ACK: SL low again).
            f_.retriggered = true;
            if (level) addRise(t);
            break;
    }
}

void BisscDecoder::onSl(Tick t, bool level) {
    ++slow_sl_edges_;
    scheduleUpTo(double(t));
    sampler_.lineEdge(t, level);
    run_.sl = level;
    drainSamples();
    checkQuiet(t);

    switch (c_.state) {
        case State::WaitSlaveIdle:
            if (level) {
                c_.state = State::Idle;
                idle();
            }
            break;
        case State::Idle:
            if (!level) {  // SL low outside a frame: not ours to decode
                c_.state = State::WaitSlaveIdle;
                idle();
            }
            break;
        case State::WaitAck:
            if (level) break;
            if (f_.rises.size() < 2) {
                addError("early_ack");
                closeFrame(t, kNoTick, nullptr, true);
                c_.state = State::WaitSlaveIdle;
                break;
            }
            resolveHoldStart(t);
            f_.ack = t;
            // The clock phases from here on (isClockPhase()); a pause before the ACK
            // is not one.
            run_.max_high = run_.max_low = 0;
            startDelayEstimate(double(t - f_.rises[1]));
            c_.state = State::Data;
            break;
        case State::Data: {
            const double late =
                double(f_.rises.back()) + run_.delay + kLateSlEdgePeriods * meanPeriod();
            if (clockedSamplesTaken() && double(t) > late) {
                // SL moved long after the last clocked slot: the master stopped early and
                // the slave timed out (or gave up).
                closeFrame(t, kNoTick, run_.slot == Slot::Busy ? "no_start" : "short_frame", true);
                c_.state = level ? State::Idle : State::WaitSlaveIdle;
            } else if (run_.slot != Slot::Done) {
                refineDelay(t);
            }
            break;
        }
        case State::Timeout:
            if (level) {
                // Decided at the next MA edge or when the clock has been quiet a period.
                f_.timeout_end = t;
                f_.ma_at_timeout_end = run_.ma;
                c_.state = State::TimeoutEnded;
                checkQuiet(t);
            }
            break;
        case State::TimeoutEnded:
            if (level) break;
            if (f_.retriggered) {  // the slave's ACK to the clocks past the stop bit
                f_.timeout_end = kNoTick;
                c_.state = State::Timeout;
            } else {  // SL fell again with MA quiet: not ours
                closeFrame(f_.timeout_end, f_.timeout_end, nullptr, true);
                c_.state = State::WaitSlaveIdle;
            }
            break;
    }
}

void BisscDecoder::scheduleUpTo(double t) {
    // Samples are scheduled just before the sampled line could pass them, so each uses
    // the line delay estimated from every SL edge seen until then.
    if (c_.state != State::Data) return;
    while (run_.scheduled < f_.rises.size()) {
        double at = sampleTime(run_.scheduled);
        if (at >= t) break;
        at = std::max(at, run_.last_sample_t);
        run_.last_sample_t = at;
        sampler_.schedule(at, std::uint32_t(run_.scheduled));
        ++run_.scheduled;
    }
}

void BisscDecoder::startDelayEstimate(double ack_delay) {
    // The ACK edge alone measures the delay to within one capture sample. The cable does
    // not change between frames: when this ACK agrees with the previous frame's refined
    // delay, that estimate (worth a few edges) steadies the samples taken before the
    // frame's own data edges refine it, i.e. in the processing-time slots.
    run_.delay_sum = ack_delay;
    run_.delay_edges = 1;
    const double tolerance = std::max(2.0, 0.25 * meanPeriod());
    if (c_.last_delay >= 0 && std::fabs(ack_delay - c_.last_delay) <= tolerance) {
        constexpr int kPriorWeight = 8;
        run_.delay_sum += kPriorWeight * c_.last_delay;
        run_.delay_edges += kPriorWeight;
    }
    run_.delay = run_.delay_sum / run_.delay_edges;
    f_.ack_delay = ack_delay;
}

void BisscDecoder::drainSamples() {
    while (sampler_.ready()) {
        const LineSampler::Sample s = sampler_.pop();
        if (c_.state == State::Data) takeSample(int(s.tag), s.level, s.t);
    }
}

void BisscDecoder::takeSample(int index, bool level, double t) {
    if (takePlainSlot(run_.slot, index, level)) return;
    switch (run_.slot) {
        case Slot::Ack:  // high: no ACK in its slot
            addError("ack");
            run_.slot = Slot::Busy;
            break;
        case Slot::Data:
            takeDataBit(level);
            break;
        case Slot::Stop:
            f_.stop_index = index;
            run_.slot = Slot::Done;
            sampler_.cancelAll();
            if (level) {
                // No low stop bit, so no timeout to wait for: the frame ends here.
                addError("stop_bit");
                closeFrame(Tick(std::ceil(t)), kNoTick, nullptr, true);
                c_.state = run_.sl ? State::Idle : State::WaitSlaveIdle;
            } else {
                c_.state = State::Timeout;
            }
            break;
        default:  // Done (the plain slots are taken above)
            break;
    }
}

void BisscDecoder::closeFrame(Tick end, Tick timeout_end, const char* error, bool feed_control) {
    if (!c_.frame_start_seen && !startedFromIdle()) {
        // The rest of a frame the capture started inside: nothing in it can be trusted.
        ++skipped_frames_;
        // But its lines were answering: the mapping's hint (framingAdvice) is not due, on
        // every path alike (the data runs do not count the edges they take).
        if (f_.ack != kNoTick) ++answered_frames_;
        sampler_.cancelAll();
        run_.slot = Slot::Done;
        idle();
        return;
    }
    c_.frame_start_seen = true;
    EventPtr owned =
        newEvent("frame", f_.start, std::max(timeout_end != kNoTick ? timeout_end : end, f_.start));
    Event& e = *owned;
    for (const auto& err : f_.errors)
        e.error(err);
    if (error) e.error(error);
    const FrameOutcome out = checkFrame(e, timeout_end);
    // Text output reads the summary alone; jsonl, verify and Python the fields alone.
    if (fieldsWanted()) addFrameFields(e, out);
    if (summariesWanted()) setFrameSummary(e, out);
    countFrame(e, out);

    ControlBits bits;
    bits.start = e.start;
    bits.end = e.end;
    bits.cdm = out.cdm;
    bits.cds = out.complete ? f_.cds : -1;

    emit(std::move(owned));
    sampler_.cancelAll();
    run_.slot = Slot::Done;
    idle();
    if (feed_control) control_.push(bits);
}

bool BisscDecoder::startedFromIdle() const {
    // A whole frame, stop bit low, that ran into the slave's timeout after the master's
    // last clock: its start bit was the slave's (the rest of a frame, parsed from a later
    // 1, would run past the master's last clock).
    if (run_.slot == Slot::Done && f_.errors.empty() && f_.timeout_end != kNoTick &&
        !f_.retriggered)
        return true;
    // Or MA had been still before the frame began for longer than its clock holds a phase
    // (only LAT seen: the low phase before it).
    double phase = double(std::max(run_.max_high, run_.max_low));
    if (phase <= 0 && f_.rises.size() >= 2) phase = periodOfRises() / 2;
    if (phase <= 0 && f_.rises.size() == 1 && !f_.from_hold) phase = double(f_.rises[0] - f_.start);
    return phase > 0 && double(f_.ma_still) > kStartIdlePhases * phase;
}

BisscDecoder::FrameOutcome BisscDecoder::checkFrame(Event& e, Tick timeout_end) {
    FrameOutcome out;
    out.complete = run_.slot == Slot::Done;
    const int pos_bits = std::min(s_.bits, s_.st_bits + s_.mt_bits);
    if (out.complete) {
        out.pos = lowBits(run_.data, pos_bits);
        if (s_.crc_bits > 0) {
            // The message: the data bits, then nE and nW (66 bits at most).
            const std::uint64_t low =
                (run_.data << 2) | std::uint64_t((f_.ne & 1) << 1) | std::uint64_t(f_.nw & 1);
            out.crc_good = crc_.of(low, run_.data >> 62) == f_.crc_rx;
            if (!out.crc_good) e.error("crc");
        }
        if (f_.ne == 0) e.error("error_bit");
        if (f_.nw == 0) e.error("warning_bit");
    }
    out.timed_out = timeout_end != kNoTick && out.complete;
    out.cdm = out.timed_out ? (f_.ma_at_timeout_end ? 0 : 1) : -1;  // MA low: CDM = 1
    if (out.timed_out) {
        out.timeout_ns = tb().toNs(timeout_end - f_.rises.back());
        if (s_.timeout_min_ns > 0 && double(out.timeout_ns) < s_.timeout_min_ns)
            e.error("timeout_short");
        // The slave's timeout (with the line delay), learnt from a frame that ran to it,
        // bounds the clock pauses later frames can have (quietLimit()); never below two
        // clock periods, so that a pulse on SL during the timeout cannot make clock
        // phases look like pauses.
        if (timeout_end > f_.rises.back()) {
            c_.slave_timeout = std::max(double(timeout_end - f_.rises.back()), 2.0 * meanPeriod());
            updateQuietTicks();
        }
    }
    out.period = meanPeriod();
    out.clocked = f_.rises.size() >= 2 && out.period > 0;
    if (out.clocked) c_.last_period = out.period;
    if (f_.ack != kNoTick) c_.last_delay = run_.delay;
    out.acked = f_.ack != kNoTick;
    out.delay_ns = out.acked ? std::llround(tb().toNsF(run_.delay)) : 0;
    return out;
}

void BisscDecoder::addFrameFields(Event& e, const FrameOutcome& out) const {
    e.fields.reserve(20);
    // Fields in place, Null where the frame did not get that far (one frame every few
    // microseconds of capture: no temporaries).
    auto add = [&e](std::string_view key, bool known, auto v) {
        if (known)
            e.add(key, v);
        else
            e.add(key, Null{});
    };
    const bool complete = out.complete, acked = out.acked, clocked = out.clocked;
    add("position", complete, out.pos);
    add("st", complete, lowBits(out.pos, s_.st_bits));
    add("mt", complete,
        s_.mt_bits > 0 ? lowBits(out.pos >> s_.st_bits, s_.mt_bits) : std::uint64_t(0));
    add("nE", complete, std::int64_t(f_.ne));
    add("nW", complete, std::int64_t(f_.nw));
    add("crc_rx", complete && s_.crc_bits > 0, std::int64_t(f_.crc_rx));
    add("crc_ok", complete && s_.crc_bits > 0, out.crc_good);
    add("cds", f_.cds >= 0, std::int64_t(f_.cds));
    add("cdm", out.timed_out, std::int64_t(out.cdm));
    add("line_delay_ns", acked, out.delay_ns);
    add("proc_cycles", f_.start_index >= 0, std::int64_t(f_.proc_cycles));
    add("ack_delay_ns", acked,
        acked ? std::int64_t(std::llround(tb().toNsF(f_.ack_delay))) : std::int64_t(0));
    add("clock_hz", clocked,
        clocked ? std::round(1.0 / (out.period * tb().secondsPerTick())) : 0.0);  // whole Hz
    add("timeout_ns", out.timed_out, out.timeout_ns);
    add("extra_clocks", f_.stop_index >= 0,
        std::int64_t(f_.rises.size()) - 1 - std::int64_t(f_.stop_index));
    e.add("clocks", std::int64_t(f_.rises.size()));
    e.add("bits", std::int64_t(s_.bits));
    e.add("crc_bits", std::int64_t(s_.crc_bits));
    e.add("hold_cdm", f_.from_hold);
    e.add("retriggered", f_.retriggered);
}

void BisscDecoder::setFrameSummary(Event& e, const FrameOutcome& out) const {
    // "pos={} (0x{:X}) nE={} nW={} crc=0x{:02X} {} cds={} cdm={} delay={}ns busy={}",
    // at most about 180 characters.
    ShortLine text;
    if (out.complete) {
        text.text("pos=").dec(out.pos).text(" (0x").hex(out.pos, 1).text(") nE=").dec(f_.ne);
        text.text(" nW=").dec(f_.nw).text(" crc=0x").hex(f_.crc_rx, 2);
        text.text(out.crc_good ? " ok cds=" : " bad cds=").dec(f_.cds).text(" cdm=");
        if (out.cdm < 0)
            text.text("?");
        else
            text.dec(out.cdm);
    } else {
        text.text("incomplete frame");
    }
    if (out.acked) text.text(" delay=").dec(out.delay_ns).text("ns");
    if (f_.proc_cycles > 0) text.text(" busy=").dec(f_.proc_cycles);
    e.summary.assign(text.view());
}

void BisscDecoder::countFrame(const Event& e, const FrameOutcome& out) {
    ++frames_;
    if (!out.acked) return;
    ++answered_frames_;
    const auto benign = [](const std::string& err) {
        return err == "error_bit" || err == "warning_bit" || err == "timeout_short" ||
               err == "glitch";
    };
    if (out.complete && s_.crc_bits > 0 && out.crc_good &&
        std::all_of(e.errors.begin(), e.errors.end(), benign))
        ++clean_frames_;
}

std::vector<std::string> BisscDecoder::advice() const {
    // A start skipped before frames that were decoded (none at all: the mapping's hint).
    std::vector<std::string> out = framingAdvice();
    if (skipped_frames_ > 0 && frames_ > 0)
        out.insert(out.begin(),
                   "the capture starts inside a frame: its rest, until MA was first seen idle, "
                   "was skipped");
    return out;
}

std::vector<std::string> BisscDecoder::framingAdvice() const {
    // Lines that change but never make an answered frame are not BiSS-C's MA and SL
    // (swapped, or other signals mapped), or the slave is not there. kMinEdges: more than
    // a stray pulse or two. Every edge takes the slow paths while no frame is answered.
    constexpr std::uint64_t kMinEdges = 16;
    if (answered_frames_ == 0 && slow_ma_edges_ + slow_sl_edges_ >= kMinEdges)
        return {fmt::format(
            "no frame got an answer from the slave ({} started; MA changed {} times, SL {} "
            "times): check that MA (the master's clock) and SL are mapped to the right signals",
            frames_, slow_ma_edges_, slow_sl_edges_)};
    // Few clean frames: a wrong width or CRC passes one frame in 64-128 by chance, and
    // faults in the traffic itself are rarely in most frames.
    if (answered_frames_ == 0 || s_.crc_bits == 0 || clean_frames_ * 8 >= answered_frames_)
        return {};
    const std::string clean =
        clean_frames_ == 0
            ? fmt::format("none of the {} answered frames", answered_frames_)
            : fmt::format("only {} of the {} answered frames", clean_frames_, answered_frames_);
    return {fmt::format(
        "{} came out clean (CRC right, stop bit low) with bits={}: check the data width "
        "(--opt bits=auto finds it from the traffic), the CRC options, and that MA and SL are "
        "not swapped",
        clean, s_.bits)};
}

void BisscDecoder::finish(Tick end) {
    scheduleUpTo(double(end));
    sampler_.advanceTo(end);
    drainSamples();
    switch (c_.state) {
        case State::WaitAck:
            // MA rising from low and nothing after: the master's return to idle.
            if (f_.from_hold && f_.rises.size() == 1) break;
            closeFrame(end, kNoTick, "short_frame", false);
            break;
        case State::Data:
            closeFrame(end, kNoTick, "short_frame", false);
            break;
        case State::Timeout:
            closeFrame(end, kNoTick, nullptr, false);
            break;
        case State::TimeoutEnded:
            closeFrame(f_.timeout_end, f_.timeout_end, nullptr, true);
            break;
        default:
            break;
    }
    c_.state = State::Idle;
    control_.finish();
}

}  // namespace busdecode
