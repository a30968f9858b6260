#include "ssi_decoder.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "core/line_sampler.h"
#include "ssi_word.h"

namespace busdecode {

namespace {

constexpr int kClk = 0;
constexpr std::size_t kMaxClocks = 8192;  // a burst longer than this is cut (overlong)
constexpr double kWaitTmFactor = 10;      // give up waiting for data high after 10 * tm_max

std::string formatHz(double hz) {
    if (hz >= 1e6) return fmt::format("{:.2f}MHz", hz / 1e6);
    if (hz >= 1e3) return fmt::format("{:.1f}kHz", hz / 1e3);
    return fmt::format("{:.0f}Hz", hz);
}

std::int64_t median(std::vector<std::int64_t> v) {
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    return v[v.size() / 2];
}

}  // namespace

SsiDecoder::SsiDecoder(const Options& o) : SsiDecoder(SsiConfig::fromOptions(o)) {}

SsiDecoder::SsiDecoder(SsiConfig cfg) : BlockDecoder("ssi"), cfg_(std::move(cfg)) {}

void SsiDecoder::start(const DecoderContext& ctx) {
    Decoder::start(ctx);
    clk_ = ctx.initial_levels.size() > 0 ? ctx.initial_levels[0] != 0 : true;
    data_ = ctx.initial_levels.size() > 1 ? ctx.initial_levels[1] != 0 : true;
    tm_max_ticks_ = tb().fromNs(cfg_.tm_max_us * 1e3);
}

double SsiDecoder::periodTicks() const {
    if (b_.falls.size() >= 2)
        return double(b_.falls.back() - b_.falls.front()) / double(b_.falls.size() - 1);
    if (!b_.rises.empty()) return 2.0 * double(b_.rises.front() - b_.falls.front());
    return 0;
}

Tick SsiDecoder::lastClock() const {
    Tick t = b_.falls.back();
    if (!b_.rises.empty()) t = std::max(t, b_.rises.back());
    return t;
}

void SsiDecoder::startBurst(Tick t) {
    b_.falls.clear();
    b_.rises.clear();
    b_.data.clear();
    b_.start = t;
    b_.falls.push_back(t);
    b_.data_at_start = data_;
    // Data still low at the first falling edge: the encoder's monoflop has not expired
    // since the last burst (a re-read of the latched word; only within tm_max of its last
    // clock, a data line stuck low is not a monoflop), or the encoder is not ready.
    b_.reread = !data_ && last_clock_ != kNoTick && !data_rose_since_clock_ &&
                double(t - last_clock_) <= tm_max_ticks_;
    b_.not_ready = !data_ && !b_.reread;
    b_.tp = last_clock_ == kNoTick ? kNoTick : t - last_clock_;
    b_.filtered_glitches = 0;
    b_.overlong = false;
    state_ = State::Clocking;
    busyFrom(t);
}

void SsiDecoder::checkTime(Tick now) {
    if (state_ == State::Clocking && clk_) {
        const double gap = cfg_.gap_bits * periodTicks();
        if (gap > 0 && double(now - lastClock()) > gap) close(false);
    }
    if (state_ == State::WaitTm && now > wait_deadline_) emitFrame(std::nullopt, true);
}

void SsiDecoder::edge(Tick t, int role, bool level) {
    checkTime(t);
    if (role == kClk) {
        clk_ = level;
        if (!level) {
            if (state_ == State::Clocking && b_.falls.size() >= kMaxClocks) {
                b_.overlong = true;
                close(false);
            }
            if (state_ == State::Clocking) {
                b_.falls.push_back(t);
            } else {
                // A new burst while the last frame still waits for tm: data is low. Within
                // tm_max a re-read (that frame's tm stays unknown), else tm was too long.
                if (state_ == State::WaitTm)
                    emitFrame(std::nullopt, double(t - last_clock_) > tm_max_ticks_);
                startBurst(t);
            }
        } else if (state_ == State::Clocking) {
            b_.rises.push_back(t);
        }
        if (state_ == State::Clocking) last_clock_ = t;
        data_rose_since_clock_ = false;
        return;
    }
    data_ = level;
    if (level) data_rose_since_clock_ = true;
    if (state_ == State::Clocking) {
        b_.data.push_back({t, level});
    } else if (state_ == State::WaitTm && level) {
        emitFrame(t, false);
    }
}

void SsiDecoder::advance(Tick now) {
    checkTime(now);
}

void SsiDecoder::glitch(Tick, int) {
    if (state_ != State::Idle) ++b_.filtered_glitches;
}

void SsiDecoder::close(bool capture_end) {
    const double T = periodTicks();
    const Tick last = lastClock();
    std::vector<std::uint8_t> data_glitch(b_.data.size(), 0);
    const int glitches = countGlitches(T, data_glitch);
    const Timing timing = measureTiming(T, data_glitch);
    const std::vector<std::uint8_t> samples = sampleBits(timing.delay);
    const SsiWord w = assembleWord(samples, cfg_);
    noteRingWidth(samples, w);
    noteTail(samples, w);
    pending_ = newEvent("frame", b_.start, last);
    fillFrame(*pending_, w, T, timing.measured, glitches);
    if (timing.late) pending_->error("late_data");
    if (timing.sample_late) pending_->error("sample_late");
    const double clock_hz = T > 0 ? tb().sampleRateHz() / T : 0.0;
    if (T > 0 && (clock_hz < cfg_.clock_min_hz || clock_hz > cfg_.clock_max_hz))
        pending_->error("clock_range");
    if (b_.not_ready) pending_->error("not_ready");
    if (b_.overlong) pending_->error("overlong");
    // The last clock edge of a complete word shifts out a separator 0 (without separators
    // it starts the next repeat): only then must data be low and tm measurable.
    pending_checks_tm_ = !w.short_frame && w.partial_bits == 0 && !b_.overlong && cfg_.ring_gap > 0;
    prev_valid_ = !w.short_frame;
    if (!w.short_frame) prev_raw_ = w.raw;
    awaitTm(last, capture_end);
}

int SsiDecoder::countGlitches(double T, std::vector<std::uint8_t>& data_glitch) const {
    // Pulses far shorter than their kind are glitches (when no glitch_ns filter removed
    // them first): a clock phase under a quarter of the median phase of its level (clock
    // duty cycles are far from 50 % on some devices), a data pulse under a quarter period.
    // Glitch data edges carry no bit and say nothing about delay.
    int glitches = b_.filtered_glitches;
    if (T <= 0) return glitches;
    std::vector<std::int64_t> lows, highs;
    for (std::size_t i = 0; i < b_.rises.size(); ++i) {
        lows.push_back(b_.rises[i] - b_.falls[i]);
        if (i + 1 < b_.falls.size()) highs.push_back(b_.falls[i + 1] - b_.rises[i]);
    }
    for (const auto* phases : {&lows, &highs}) {
        if (phases->empty()) continue;
        const double shortest = double(median(*phases)) / 4;
        for (auto p : *phases)
            if (double(p) < shortest) ++glitches;
    }
    const double shortest = T / 4;
    for (std::size_t i = 1; i < b_.data.size(); ++i) {
        if (double(b_.data[i].t - b_.data[i - 1].t) < shortest) {
            if (!data_glitch[i - 1]) ++glitches;
            data_glitch[i - 1] = data_glitch[i] = 1;
        }
    }
    return glitches;
}

SsiDecoder::Timing SsiDecoder::measureTiming(double T,
                                             const std::vector<std::uint8_t>& data_glitch) {
    const bool rising = cfg_.sample_rising;
    const std::vector<Tick>& S = rising ? b_.rises : b_.falls;  // sampling edges
    // Data delay: each data edge measured from the latest rising edge (the encoder shifts
    // on rising edges; a bit launched by rising edge k is sampled by sampling edge k+1, the
    // first one after it, in both sampling modes). That gives the delay modulo a period;
    // the whole periods come from periodRange().
    const std::vector<Tick>& L = b_.rises;
    // Rising edges at or before each data edge: both are in time order, one sweep.
    rises_before_.resize(b_.data.size());
    for (std::size_t i = 0, r = 0; i < b_.data.size(); ++i) {
        while (r < L.size() && L[r] <= b_.data[i].t)
            ++r;
        rises_before_[i] = r;
    }
    std::vector<std::int64_t>& offsets = offsets_;
    offsets.clear();
    for (std::size_t i = 0; i < b_.data.size(); ++i) {
        if (data_glitch[i] || rises_before_[i] == 0) continue;
        const Tick off = b_.data[i].t - L[rises_before_[i] - 1];
        if (T <= 0 || double(off) < T) offsets.push_back(off);
    }
    Timing out;
    const std::int64_t frac = offsets.empty() ? 0 : median(offsets);
    double to_sample = 0;  // mean time from a launching edge to the sample of its bit
    int n = 0;
    for (std::size_t k = 0; k + 1 < S.size() && k < L.size(); ++k, ++n)
        to_sample += double(S[k + 1] - L[k]);
    to_sample = n > 0 ? to_sample / n : (rising ? T : T / 2);
    out.delay = tb().fromNs(cfg_.delay_ns);
    // Whole periods: those the last frame had (the cable stays the same; at first, those
    // in the given offset itself, none with auto), within what this frame's edges allow.
    const auto [lo, hi] = periodRange(T, frac, data_glitch);
    const double offset_periods = cfg_.delay_auto ? 0.0 : out.delay / std::max(T, 1.0);
    int whole = whole_periods_ >= 0 ? whole_periods_
                                    : int(std::floor(std::clamp(offset_periods, 0.0, 1e6)));
    whole = std::max(lo, std::min(whole, std::max(lo, hi)));
    whole_periods_ = whole;
    out.measured = frac + std::llround(whole * T);
    // Sample in the middle of each bit's window [launch + delay, next launch + delay).
    if (cfg_.delay_auto) out.delay = double(out.measured) + T / 2 - to_sample;
    checkWindows(T, frac, whole, out, data_glitch);
    return out;
}

std::pair<int, int> SsiDecoder::periodRange(double T, std::int64_t frac,
                                            const std::vector<std::uint8_t>& data_glitch) const {
    // No data edge comes before the first rising edge plus the delay: the first one bounds
    // the whole periods from above (exact when the MSB is 0). Falling edges after the last
    // clock are bits (the monoflop's return is a rise) launched by at most the last rising
    // edge: they bound it from below (exact when the LSB is 1), when they sit on the
    // delay's grid (not a line that breaks low after the burst).
    const std::vector<Tick>& L = b_.rises;
    int lo = 0, hi = std::numeric_limits<int>::max();
    if (T <= 0 || L.empty()) return {0, hi};
    bool first = true;
    for (std::size_t i = 0; i < b_.data.size(); ++i) {
        const Tick e = b_.data[i].t;
        if (data_glitch[i] || e < L.front()) continue;
        const auto periods = [&](Tick from) {
            return std::min(std::round(double(e - from - frac) / T), double(1 << 20));
        };
        if (first) hi = std::max(0, int(periods(L.front())));
        first = false;
        if (b_.data[i].level || e <= L.back()) continue;
        const double j = periods(L.back());
        if (std::abs(double(e - L.back() - frac) - j * T) < T / 4) lo = std::max(lo, int(j));
    }
    return {lo, hi};
}

void SsiDecoder::checkWindows(double T, std::int64_t frac, int whole, Timing& out,
                              const std::vector<std::uint8_t>& data_glitch) const {
    // Each bit must be sampled inside its window. A data edge at or after the sample
    // that should have seen it: the data came too late (`late_data`). A data edge at or
    // before the sample of the bit it ends: the sampling offset is too late
    // (`sample_late`). Either way a bit was misread.
    const std::vector<Tick>& S = cfg_.sample_rising ? b_.rises : b_.falls;
    const std::vector<Tick>& L = b_.rises;
    for (std::size_t i = 0; i < b_.data.size(); ++i) {
        const std::size_t before = rises_before_[i];
        if (data_glitch[i] || before == 0) continue;
        const Tick t = b_.data[i].t;
        // Launched `whole` rising edges before the latest one; past the last one, as many
        // fewer as whole periods have gone since it.
        auto k = std::int64_t(before) - 1 - whole;
        const Tick off = t - L[before - 1];
        if (T > 0 && double(off) >= T) {
            if (before != L.size()) continue;  // a long clock phase: not on the delay grid
            k += std::lround(double(off - frac) / T);
        }
        if (k < 0 || k >= std::int64_t(L.size())) continue;  // the monoflop return
        const double e = double(t);
        const auto u = std::size_t(k);
        if (u + 1 < S.size() && e >= double(S[u + 1]) + out.delay) out.late = true;
        if (u < S.size() && e <= double(S[u]) + out.delay) out.sample_late = true;
    }
}

std::vector<std::uint8_t> SsiDecoder::sampleBits(double delay) const {
    const std::vector<Tick>& S = cfg_.sample_rising ? b_.rises : b_.falls;
    LineSampler sampler;
    sampler.reset(b_.data_at_start);
    for (std::size_t i = 0; i < S.size(); ++i)
        sampler.schedule(double(S[i]) + delay, 0);
    for (const auto& d : b_.data)
        sampler.lineEdge(d.t, d.level);
    sampler.flush();
    std::vector<std::uint8_t> samples;
    samples.reserve(S.size());
    bool first = true;
    while (sampler.ready()) {
        const bool bit = sampler.pop().level;
        if (first && !cfg_.lead) {
            first = false;  // the latch edge's sample is not a bit
            continue;
        }
        first = false;
        samples.push_back(bit);
    }
    return samples;
}

void SsiDecoder::fillFrame(Event& e, const SsiWord& w, double T, std::int64_t measured,
                           int glitches) {
    const SsiFields f = w.short_frame ? SsiFields{} : splitFields(w.raw, cfg_);
    e.fields.reserve(20 + cfg_.status.size());
    e.set("raw", w.raw);
    e.set("bits", std::int64_t(w.bits));
    std::vector<std::int64_t> diff = w.diff_bits;
    bool match = w.repeat_match;
    if (!w.short_frame) {
        e.set("position", f.position);
        e.set("st", f.st);
        e.set("mt", f.mt);
        e.set("angle", f.angle ? Value(*f.angle) : Value(Null{}));
        if (b_.reread && prev_valid_) {
            // The encoder has not updated since the last burst: the same word again.
            const std::uint64_t d = (w.raw ^ prev_raw_) & cfg_.dataMask();
            if (d) {
                match = false;
                for (auto b : bitList(d))
                    if (std::find(diff.begin(), diff.end(), b) == diff.end()) diff.push_back(b);
                std::sort(diff.begin(), diff.end());
            }
        }
    } else {
        e.set("position", Null{});
        e.set("st", Null{});
        e.set("mt", Null{});
        e.set("angle", Null{});
    }
    e.set("repeats", std::int64_t(w.repeats));
    e.set("repeat_match", match);
    const double clock_hz = T > 0 ? tb().sampleRateHz() / T : 0.0;
    e.set("clock_hz", T > 0 ? Value(clock_hz) : Value(Null{}));
    e.set("tm_ns", Null{});
    e.set("tp_ns", b_.tp == kNoTick ? Value(Null{}) : Value(tb().toNs(b_.tp)));
    e.set("delay_ns", tb().toNs(measured));
    e.set("reread", b_.reread);
    e.set("partial_bits", std::int64_t(w.partial_bits));
    e.set("repeat_diff_bits", diff);
    if (!w.short_frame) {
        e.set("status", f.status);
        for (const auto& s : cfg_.status)
            e.set(s.name, bool(w.raw >> s.bit & 1));
        if (f.parity_ok) {
            e.set("parity_ok", *f.parity_ok);
            if (!*f.parity_ok) e.error("parity");
        }
    }
    e.set("glitches", std::int64_t(glitches));
    if (w.short_frame) e.error("short_frame");
    if (!match) e.error("repeat_mismatch");
    if (!w.separator_ok) e.error("ring_separator");
    if (glitches > 0) e.error("glitch");
    if (summariesWanted()) e.summary = frameSummary(w, f, diff, T);  // text output, reports
}

std::string SsiDecoder::frameSummary(const SsiWord& w, const SsiFields& f,
                                     const std::vector<std::int64_t>& diff, double T) const {
    // Summary text (tm is added when known).
    std::string text;
    if (w.short_frame) {
        text = fmt::format("short frame: {} of {} bits raw=0x{:X}", w.bits, cfg_.bits, w.raw);
    } else {
        text = fmt::format("raw=0x{:X} pos=0x{:X}", w.raw, f.position);
        if (cfg_.mt_bits > 0) text += fmt::format(" mt=0x{:X}", f.mt);
        if (cfg_.st_bits > 0) text += fmt::format(" st=0x{:X} angle={:.2f}", f.st, *f.angle);
        for (const auto& s : cfg_.status)
            if (w.raw >> s.bit & 1) text += " " + s.name;
        text += fmt::format(" repeats={}", w.repeats);
        if (w.partial_bits) text += fmt::format("+{}b", w.partial_bits);
        if (!diff.empty()) text += fmt::format(" diff_bits={}", fmt::join(diff, ","));
    }
    if (b_.reread) text += " reread";
    if (T > 0) text += " clk=" + formatHz(tb().sampleRateHz() / T);
    return text;
}

void SsiDecoder::awaitTm(Tick last, bool capture_end) {
    // tm: from the last clock edge to data returning high.
    for (const auto& d : b_.data) {
        if (d.t > last && d.level) {
            emitFrame(d.t, false);
            return;
        }
    }
    if (data_ || capture_end) {
        // Data high and no low period after the last clock: nothing to measure. A complete
        // word must be followed by a low level (line break / no encoder otherwise).
        if (!capture_end && pending_checks_tm_) pending_->error("tm_missing");
        pending_checks_tm_ = false;
        emitFrame(std::nullopt, false);
        return;
    }
    state_ = State::WaitTm;
    // At most 1e18 ticks ahead: tm_max_us may be anything up to 1e300, and edge times go
    // up to 2^62, so the sum stays in range (fuzz finding: overflow with a huge tm_max_us).
    const double wait = std::min(tb().fromNs(cfg_.tm_max_us * 1e3 * kWaitTmFactor), 1e18);
    wait_deadline_ = last + Tick(std::llround(wait));
}

void SsiDecoder::emitFrame(std::optional<Tick> tm_end, bool deadline_passed) {
    Event& e = *pending_;
    std::optional<std::int64_t> measured_tm_ns;
    if (tm_end) {
        const std::int64_t tm_ns = tb().toNs(*tm_end - e.end);
        measured_tm_ns = tm_ns;
        e.set("tm_ns", tm_ns);
        if (pending_checks_tm_) {
            tm_values_.push_back(tm_ns);
            if (double(tm_ns) < cfg_.tm_min_us * 1e3) e.error("timeout_short");
            if (double(tm_ns) > cfg_.tm_max_us * 1e3) e.error("timeout_long");
        }
    } else if (deadline_passed && pending_checks_tm_) {
        e.error("timeout_long");
    }
    if (summariesWanted())  // text output and reports; jsonl and Python read tm_ns
        e.summary += measured_tm_ns ? fmt::format(" tm={:.1f}us", double(*measured_tm_ns) / 1e3)
                                    : std::string(" tm=?");

    ++frames_;
    if (e.hasError("repeat_mismatch")) ++mismatches_;
    if (e.hasError("short_frame")) {
        const Value* b = e.get("bits");  // the bits the short frame had
        const std::int64_t bits = b ? asInt(*b) : -1;
        short_bits_ = ++shorts_ == 1 || short_bits_ == bits ? bits : -1;
    }
    if (!e.errors.empty()) ++error_frames_;
    if (const Value* c = e.get("clock_hz"); c && !isNull(*c)) {
        const double hz = asDouble(*c);
        clock_min_ = frames_ == 1 || clock_min_ == 0 ? hz : std::min(clock_min_, hz);
        clock_max_ = std::max(clock_max_, hz);
    }
    emit(std::move(pending_));
    state_ = State::Idle;
    idle();
}

void SsiDecoder::emitSummary(Tick end) {
    EventPtr owned = newEvent("summary", end, end);
    Event& e = *owned;
    e.set("frames", frames_);
    Value tmin = Null{}, tmed = Null{}, tmax = Null{};
    if (!tm_values_.empty()) {
        tmin = *std::min_element(tm_values_.begin(), tm_values_.end());
        tmax = *std::max_element(tm_values_.begin(), tm_values_.end());
        tmed = median(tm_values_);
    }
    e.set("tm_min_ns", tmin);
    e.set("tm_median_ns", tmed);
    e.set("tm_max_ns", tmax);
    e.set("clock_hz_min", clock_max_ > 0 ? Value(clock_min_) : Value(Null{}));
    e.set("clock_hz_max", clock_max_ > 0 ? Value(clock_max_) : Value(Null{}));
    e.set("repeat_mismatches", mismatches_);
    e.set("short_frames", shorts_);
    e.set("error_frames", error_frames_);
    std::string text = fmt::format("{} frames", frames_);
    if (!tm_values_.empty())
        text += fmt::format(" tm min/median/max={:.1f}/{:.1f}/{:.1f}us", asDouble(tmin) / 1e3,
                            asDouble(tmed) / 1e3, asDouble(tmax) / 1e3);
    if (clock_max_ > 0) text += " clk " + formatHz(clock_min_) + ".." + formatHz(clock_max_);
    text += fmt::format(" repeat_mismatches={} short_frames={} error_frames={}", mismatches_,
                        shorts_, error_frames_);
    e.summary = std::move(text);
    emit(std::move(owned));
}

void SsiDecoder::finish(Tick end) {
    checkTime(end);
    if (state_ == State::Clocking) close(true);
    if (state_ == State::WaitTm) emitFrame(std::nullopt, false);
    if (cfg_.summary) emitSummary(end);
    idle();
}

void SsiDecoder::noteRingWidth(const std::vector<std::uint8_t>& samples, const SsiWord& w) {
    // The first frames are enough to tell, and keep the search off long captures.
    constexpr std::int64_t kFramesLooked = 64;
    if (cfg_.lead || w.short_frame || ring_looked_ >= kFramesLooked) return;
    if (ring_looked_++ == 0) ring_first_raw_ = w.raw;
    // A still encoder repeats a chance pattern in every frame: words that differ count.
    ring_varied_ = ring_varied_ || w.raw != ring_first_raw_;
    // A frame clocked past 64 bits may repeat after more than a word holds: no ring, as 0.
    const int width = ringWidth(samples, cfg_.ring_gap);
    ++ring_votes_[width < int(ring_votes_.size()) ? std::size_t(width) : 0];
}

void SsiDecoder::noteTail(const std::vector<std::uint8_t>& samples, const SsiWord& w) {
    const int past = int(samples.size()) - cfg_.bits;
    if (cfg_.lead || w.short_frame || w.repeats != 1 || past < 1 || past > cfg_.ring_gap) return;
    tail_bits_ = tail_frames_++ == 0 || tail_bits_ == past ? past : -1;
    if (!w.separator_ok) ++tail_ones_;
}

std::vector<std::string> SsiDecoder::tailAdvice() const {
    // A master may clock one bit past the word to see the line low; a 1 there in some
    // frames is the word's own last bit.
    if (frames_ < 2 || tail_frames_ != frames_ || tail_ones_ == 0 || tail_bits_ <= 0) return {};
    const int word = cfg_.bits + tail_bits_;
    return {fmt::format(
        "every frame was clocked {} bit{} past bits={} with no repeat, and in {} of {} frames "
        "a 1 came where the 0 after the word belongs: the words look {} bits long (--opt "
        "bits={}{})",
        tail_bits_, tail_bits_ == 1 ? "" : "s", cfg_.bits, tail_ones_, frames_, word, word,
        cfg_.st_bits + cfg_.mt_bits + cfg_.pos_shift <= word
            ? ""
            : ", with st_bits and mt_bits to fit")};
}

int SsiDecoder::ringWidthFound() const {
    // Some words repeat a shorter pattern by chance: three frames in four must agree.
    if (!ring_varied_ || ring_looked_ < 4) return 0;
    for (int n = 1; n < int(ring_votes_.size()); ++n)
        if (ring_votes_[std::size_t(n)] * 4 >= ring_looked_ * 3) return n;
    return 0;
}

std::vector<std::string> SsiDecoder::advice() const {
    // The frames looked at held the same word again after `ring` bits.
    if (const int ring = ringWidthFound(); ring > 0 && ring < cfg_.bits)
        return {fmt::format(
            "every frame repeats a {}-bit word ({} zero bits between, the encoder's ring shift) "
            "within bits={}: the words look {} bits long (--opt bits={}{})",
            ring, cfg_.ring_gap, cfg_.bits, ring, ring,
            cfg_.st_bits + cfg_.mt_bits + cfg_.pos_shift <= ring
                ? ""
                : ", with st_bits and mt_bits to fit")};
    // One short frame is a master that stopped early; all of them, each with the same
    // count, is a word of that length.
    if (frames_ < 2 || shorts_ != frames_ || short_bits_ <= 0) return tailAdvice();
    const bool fields_fit = cfg_.st_bits + cfg_.mt_bits + cfg_.pos_shift <= short_bits_;
    // One bit short without `lead`: the first clock edge's level may be a bit (POSITAL).
    const bool lead_fits = !cfg_.lead && short_bits_ + 1 == cfg_.bits;
    return {
        fmt::format("every frame ended after {} bits, short of bits={}: the words look {} "
                    "bits long (--opt bits={}{}{})",
                    short_bits_, cfg_.bits, short_bits_, short_bits_,
                    fields_fit ? "" : ", with st_bits and mt_bits to fit",
                    lead_fits ? "; or --opt lead=1, if the level at the first clock edge "
                                "is a bit"
                              : "")};
}

}  // namespace busdecode
