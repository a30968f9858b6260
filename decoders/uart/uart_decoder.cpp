#include "uart_decoder.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "core/options.h"
#include "core/registry.h"

namespace busdecode {

namespace {

constexpr int kRx = 0, kTx = 1;
// baud=auto measures this many edges before decoding (then replays them): enough for a
// one-bit pulse to appear in any realistic traffic, small enough to hold in memory.
constexpr std::size_t kAutoBaudEdges = 400;

std::uint32_t tagOf(std::uint32_t generation, int slot) {
    return (generation << 8) | std::uint32_t(slot);
}

std::string printable(std::uint32_t v) {
    if (v >= 0x20 && v < 0x7F) return fmt::format(" '{}'", char(v));
    return "";
}

}  // namespace

UartDecoder::UartDecoder(const Options& options) : BlockDecoder("uart") {
    fmt_ = UartFormat::fromOptions(options);
    auto_baud_ = options.isAuto("baud");
    estimator_ = BaudEstimator(2, !fmt_.invert);
    lines_[kRx].name = "rx";
    lines_[kTx].name = "tx";
}

void UartDecoder::start(const DecoderContext& ctx) {
    Decoder::start(ctx);
    for (int r = 0; r < 2; ++r) {
        const int initial = r < int(ctx.initial_levels.size()) ? ctx.initial_levels[r] : -1;
        Line& l = lines_[r];
        l.bound = initial >= 0;
        l.level = initial != 0;
        l.sampler.reset(l.level);
    }
    if (!auto_baud_) bit_ticks_ = tb().fromSeconds(1.0 / fmt_.baud);
    // With fewer than two ticks a bit, no sample point lies inside each bit: every byte
    // would come out wrong, with no fault to show it.
    if (!auto_baud_ && bit_ticks_ < 2)
        throw InputError(fmt::format(
            "decoder uart: option baud={:g}: a bit lasts {:g} s, less than two ticks of the "
            "capture's time base ({:g} s a tick): its bits cannot be told apart (capture with a "
            "finer time base)",
            fmt_.baud, 1.0 / fmt_.baud, tb().secondsPerTick()));
}

void UartDecoder::edge(Tick t, int role, bool level) {
    if (role < 0 || role > 1) return;
    if (bit_ticks_ > 0) {
        // The first edges also measure the rate, to check a given baud against (advice()).
        if (checked_edges_ < kAutoBaudEdges) {
            ++checked_edges_;
            estimator_.addEdge(t, role, level);
        }
        decodeEdge(t, role, level);
        return;
    }
    if (held_.empty()) busyFrom(t);
    held_.push_back({t, role, level});
    estimator_.addEdge(t, role, level);
    if (held_.size() >= kAutoBaudEdges) decideBaud();
}

void UartDecoder::decideBaud() {
    const auto measured = estimator_.measuredBaud(tb());
    fmt_.baud = measured ? BaudEstimator::snapToStandard(*measured) : fmt_.baud;
    // A measurement from absurdly long pulses stays within the option's range, so frame
    // times stay far inside the tick range (found by fuzzing: 1e-3 baud overflowed).
    fmt_.baud = std::clamp(fmt_.baud, 1.0, 1e9);
    bit_ticks_ = tb().fromSeconds(1.0 / fmt_.baud);
    if (measured && !held_.empty()) {
        EventPtr owned = newEvent("baud", held_.front().t, held_.front().t);
        Event& e = *owned;
        e.set("baud", fmt_.baud);
        e.set("measured_baud", *measured);
        e.summary = fmt::format("baud rate {:g} (measured {:.1f} from the shortest pulses)",
                                fmt_.baud, *measured);
        emit(std::move(owned));
    }
    std::vector<HeldEdge> replay;
    replay.swap(held_);
    idle();
    for (const auto& h : replay)
        decodeEdge(h.t, h.role, h.level);
}

void UartDecoder::decodeEdge(Tick t, int role, bool level) {
    // Edges arrive in time order over both lines: the other line has no edge before t,
    // so its samples up to t are settled now (keeps rx and tx bytes in time order).
    settleOtherLines(t, role);
    Line& l = lines_[role];
    l.sampler.lineEdge(t, level);
    drain(l);
    l.level = level;
    const bool logical = level != fmt_.invert;  // true = idle (mark)
    if (l.in_break && logical) emitBreak(l, t);
    if (!l.in_frame && !l.in_break && !logical) startFrame(l, t);
    updateBusy();
}

void UartDecoder::settleOtherLines(Tick t, int except) {
    for (int r = 0; r < 2; ++r) {
        if (r == except || !lines_[r].bound) continue;
        lines_[r].sampler.advanceTo(t);
        drain(lines_[r]);
    }
}

void UartDecoder::advance(Tick now) {
    if (bit_ticks_ <= 0) return;
    settleOtherLines(now, -1);
    updateBusy();
}

void UartDecoder::finish(Tick end) {
    if (bit_ticks_ <= 0) decideBaud();
    for (auto& l : lines_) {
        if (!l.bound) continue;
        l.sampler.advanceTo(end + 1);  // a sample on the last tick still sees the line
        drain(l);
        if (l.in_frame) endFrame(l, true);
        if (l.in_break) emitBreak(l, end);
    }
    updateBusy();
}

double UartDecoder::samplePoint(Tick frame_start, int slot) const {
    // Mid-bit, counted as sigrok does: ceil(start + (bit-1)/2 + slot*bit), so sample
    // indices of .sr captures match its expected outputs exactly.
    const int before_stop = fmt_.slotsBeforeStop();
    if (slot < before_stop + 1) {
        double width = bit_ticks_;
        if (slot == before_stop) width = std::min(1.0, fmt_.stop_bits) * bit_ticks_;
        double p = (width - 1) * 0.5;
        p += double(frame_start);
        p += slot * bit_ticks_;
        return std::ceil(p);
    }
    // The second stop bit (or the half of 1.5).
    const double width = (fmt_.stop_bits - 1) * bit_ticks_;
    double p = (width - 1) * 0.5;
    p += double(frame_start);
    p += slot * bit_ticks_;
    return std::ceil(p);
}

Tick UartDecoder::frameEnd(Tick frame_start) const {
    return frame_start + Tick(std::llround(fmt_.frameBits() * bit_ticks_));
}

void UartDecoder::startFrame(Line& l, Tick t) {
    l.in_frame = true;
    l.frame_start = t;
    l.value = 0;
    l.parity_bit = false;
    l.stop_ok = true;
    l.all_low = true;
    ++l.generation;
    const int stop_samples = fmt_.stop_bits > 1 ? 2 : 1;
    const int slots = fmt_.slotsBeforeStop() + stop_samples;
    for (int s = 0; s < slots; ++s)
        l.sampler.schedule(samplePoint(t, s), tagOf(l.generation, s));
}

void UartDecoder::drain(Line& l) {
    while (l.sampler.ready()) {
        const auto s = l.sampler.pop();
        if ((s.tag >> 8) != (l.generation & 0xFFFFFF) || !l.in_frame) continue;
        onSample(l, s);
    }
}

void UartDecoder::onSample(Line& l, const LineSampler::Sample& s) {
    const int slot = int(s.tag & 0xFF);
    const bool bit = s.level != fmt_.invert;
    const int before_stop = fmt_.slotsBeforeStop();
    const int last_slot = before_stop + (fmt_.stop_bits > 1 ? 1 : 0);
    if (slot == 0) {
        if (bit) {
            // The line was high again mid-start-bit: a glitch, not a character.
            l.in_frame = false;
            ++l.generation;
            l.sampler.cancelAll();
        }
        return;
    }
    l.all_low = l.all_low && !bit;
    if (slot <= fmt_.bits) {
        const int i = slot - 1;
        if (fmt_.lsb_first)
            l.value |= std::uint32_t(bit) << i;
        else
            l.value = (l.value << 1) | std::uint32_t(bit);
    } else if (fmt_.hasParityBit() && slot == before_stop - 1) {
        l.parity_bit = bit;
    } else {
        l.stop_ok = l.stop_ok && bit;
    }
    if (slot == last_slot) endFrame(l, false);
}

void UartDecoder::endFrame(Line& l, bool cut_short) {
    l.in_frame = false;
    ++l.generation;
    l.sampler.cancelAll();
    EventPtr owned = newEvent("byte", l.frame_start, frameEnd(l.frame_start));
    Event& e = *owned;
    if (cut_short) {
        e.set("value", Null{});
        e.set("line", l.name);
        e.error("short_frame");
        e.summary = fmt::format("{} (capture ended mid-character)", l.name);
        emit(std::move(owned));
        return;
    }
    e.set("value", std::int64_t(l.value));
    e.set("line", l.name);
    const bool checks_parity = fmt_.hasParityBit() && fmt_.parity != Parity::Ignore;
    if (checks_parity) {
        const bool ok = l.parity_bit == fmt_.parityBitFor(l.value);
        e.set("parity_ok", ok);
        if (!ok) e.error("parity");
    }
    if (!l.stop_ok) e.error("framing");
    ++bytes_;
    faulty_bytes_ += !e.errors.empty();
    if (summariesWanted()) {  // text output and reports; jsonl and Python read the fields
        const int hex_digits = (fmt_.bits + 3) / 4;
        e.summary = fmt::format("{} 0x{:0{}X}{}", l.name, l.value, hex_digits, printable(l.value));
    }
    emit(std::move(owned));
    // Low through every sample, stop bits included: a break if the line stays low to the
    // frame's end, reported when it ends.
    if (l.all_low && !l.stop_ok && (l.level == fmt_.invert)) {
        l.in_break = true;
        l.break_start = l.frame_start;
    }
}

void UartDecoder::emitBreak(Line& l, Tick end) {
    l.in_break = false;
    // Low past the last stop bit's sample but not for a whole frame (give or take the tick
    // the edges are quantised to): no break, nor in sigrok's decoder (below 10 bit times
    // at 8N1).
    if (double(end - l.break_start) + 1 < fmt_.frameBits() * bit_ticks_) return;
    EventPtr owned = newEvent("break", l.break_start, end);
    Event& e = *owned;
    e.set("line", l.name);
    e.set("duration_ns", tb().toNs(end - l.break_start));
    e.summary = fmt::format("{} break ({} bit times)", l.name,
                            std::llround(double(end - l.break_start) / bit_ticks_));
    emit(std::move(owned));
}

void UartDecoder::updateBusy() {
    Tick busy = kNoTick;
    auto take = [&](Tick t) {
        if (busy == kNoTick || t < busy) busy = t;
    };
    for (const auto& l : lines_) {
        if (l.in_frame) take(l.frame_start);
        if (l.in_break) take(l.break_start);
    }
    if (!held_.empty()) take(held_.front().t);
    if (busy == kNoTick)
        idle();
    else
        setBusyFrom(busy);
}

std::optional<std::string> UartDecoder::baudHint() const {
    // A given rate the pulses contradict: read too slow, a few long garbled characters
    // (TMCL sees datagrams cut short); too fast, every character a framing error.
    constexpr std::size_t kMinPulses = 16;
    if (auto_baud_ || estimator_.pulses() < kMinPulses) return std::nullopt;
    const auto measured = estimator_.measuredBaud(tb());
    if (!measured) return std::nullopt;
    const double standard = BaudEstimator::snapToStandard(*measured);
    // Pulses longer than a bit at the given rate are whole characters of ones or zeros
    // as often as a slower rate: only faults make them evidence.
    const bool off = std::fabs(standard - fmt_.baud) > 0.1 * fmt_.baud;
    if (!off || (standard < fmt_.baud && faulty_bytes_ == 0)) return std::nullopt;
    return fmt::format(
        "the shortest pulses are {:.1f} us, a bit at {:g} baud, not at baud={:g} ({} of {} "
        "characters with framing or parity errors): try --opt baud={:g} (or baud=auto)",
        1e6 / *measured, standard, fmt_.baud, faulty_bytes_, bytes_, standard);
}

std::vector<std::string> UartDecoder::advice() const {
    if (auto hint = baudHint()) return {*hint};
    // A wrong rate, format or polarity garbles nearly every character; noise or a
    // collision rarely most of them. kMinBytes: enough characters to tell.
    constexpr std::uint64_t kMinBytes = 8;
    if (bytes_ < kMinBytes || faulty_bytes_ * 2 <= bytes_) return {};
    static constexpr const char* kParity[] = {"none", "even", "odd", "mark", "space", "ignore"};
    return {fmt::format(
        "{} of {} characters have framing or parity errors at baud={:g}{} (bits={} parity={} "
        "stop={:g} invert={}): check {}the character format, and the lines' polarity",
        faulty_bytes_, bytes_, fmt_.baud, auto_baud_ ? " as measured" : "", fmt_.bits,
        kParity[int(fmt_.parity)], fmt_.stop_bits, int(fmt_.invert),
        auto_baud_ ? "" : "the baud rate (--opt baud=auto measures it), ")};
}

}  // namespace busdecode
