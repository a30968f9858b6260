#include "spi_decoder.h"

#include <limits>

#include "core/number_text.h"
#include "spi_info.h"

namespace busdecode {

SpiDecoder::SpiDecoder(const Options& o)
    : cpol_(int(o.integer("cpol"))),
      cpha_(int(o.integer("cpha"))),
      bits_(int(o.integer("bits"))),
      lsb_first_(o.flag("lsb_first")),
      cs_active_high_(o.text("cs_polarity") == "active-high"),
      // Modes 0 and 3 sample on the rising edge, modes 1 and 2 on the falling edge.
      sample_on_rising_(cpol_ == cpha_),
      mosi_(o.flag("lsb_first")),
      miso_(o.flag("lsb_first")) {}

void SpiDecoder::start(const DecoderContext& ctx) {
    Decoder::start(ctx);
    bound_ = level_ = settled_ = 0;
    for (int r = 0; r < kSpiRoleCount; ++r) {
        int lv = r < int(ctx.initial_levels.size()) ? ctx.initial_levels[r] : -1;
        if (lv >= 0) bound_ |= bit(r);
        if (lv == 1) level_ |= bit(r);
    }
    settled_ = level_;
    group_open_ = false;
    resetWord();
}

// Inlined whole into the block loop (BlockDecoder::edges calls it for every edge; left
// to itself GCC inlines only the role check, 10 % slower by bench_micro decode/spi).
// GCC's -Wattributes note that an always_inline virtual "might not be inlinable" is
// about virtual calls, which use the out-of-line copy.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wattributes"
#endif
[[gnu::always_inline]] void SpiDecoder::edge(Tick t, int role, bool level) {
    if (unsigned(role) >= unsigned(kSpiRoleCount)) return;
    if (group_open_ && t > group_tick_) settle();
    level_ = (level_ & ~bit(role)) | (unsigned(level) << role);
    group_tick_ = t;
    group_open_ = true;
    busyFrom(t);
}
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif

void SpiDecoder::advance(Tick now) {
    if (group_open_ && now > group_tick_) settle();
}

void SpiDecoder::settle() {
    group_open_ = false;
    const Tick t = group_tick_;
    const unsigned changed = level_ ^ settled_;
    if (changed & bound_ & bit(kSpiCs)) {
        // Any cs change ends the word in progress (sigrok resets its state likewise).
        if (count_ > 0 && csActive(settled_)) emitWord(t, true);
        resetWord();
    }
    const bool sampling =
        (changed & bit(kSpiSclk)) && bool(level_ & bit(kSpiSclk)) == sample_on_rising_;
    settled_ = level_;
    if (sampling && (!(bound_ & bit(kSpiCs)) || csActive(level_))) sampleBit(t);
    if (count_ > 0)
        setBusyFrom(word_start_);
    else
        idle();
}

void SpiDecoder::sampleBit(Tick t) {
    if (count_ == 0) {
        word_start_ = t;
        prev_sample_ = t;
    } else {
        prev_sample_ = last_sample_;
    }
    last_sample_ = t;
    if (bound_ & bit(kSpiMosi)) mosi_.push(level_ & bit(kSpiMosi));
    if (bound_ & bit(kSpiMiso)) miso_.push(level_ & bit(kSpiMiso));
    ++count_;
    if (count_ == bits_) {
        // sigrok's end estimate: one bit period (the last sample interval) after the last bit.
        // Saturated: an absurd gap before the last bit must not overflow (fuzz finding;
        // period >= 0 as edges come in time order, so max - period cannot overflow).
        const Tick period = t - prev_sample_;
        emitWord(t > std::numeric_limits<Tick>::max() - period ? std::numeric_limits<Tick>::max()
                                                               : t + period,
                 false);
        resetWord();
    }
}

void SpiDecoder::emitWord(Tick end, bool short_frame) {
    Event e;
    e.proto = "spi";
    e.type = "transfer";
    e.start = word_start_;
    e.end = std::max(end, word_start_);
    const int n = count_;
    const int digits = (n + 3) / 4;
    ShortLine text;  // at most 64 bits: "MOSI 0x" + 16 digits, twice, and the short note
    bool first = true;
    auto put = [&](const char* key, const char* label, const BitWord& w, bool bound) {
        if (!bound) {
            e.add(key, Null{});
            return;
        }
        // MSB-first words keep the newest 64 bits; LSB-first words the first 64.
        std::uint64_t v = lowBits(w.value(), n);
        e.add(key, v);
        if (!first) text.text(" ");
        first = false;
        text.text(label).text(" 0x").hex(v, digits);
    };
    put("mosi", "MOSI", mosi_, bound_ & bit(kSpiMosi));
    put("miso", "MISO", miso_, bound_ & bit(kSpiMiso));
    e.add("bits", std::int64_t(n));
    if (short_frame) {
        e.error("short_frame");
        text.text(" (").dec(n).text(" of ").dec(bits_).text(" bits)");
    }
    if (word_glitch_) e.error("glitch");
    e.summary.assign(text.view());
    emit(std::move(e));
}

void SpiDecoder::resetWord() {
    mosi_.clear();
    miso_.clear();
    count_ = 0;
    word_glitch_ = false;
}

void SpiDecoder::glitch(Tick t, int role) {
    (void)t;
    // A removed pulse on a line of the word in progress makes that word doubtful.
    if (role == kSpiSclk || role == kSpiMosi || role == kSpiMiso || role == kSpiCs)
        if (count_ > 0) word_glitch_ = true;
}

void SpiDecoder::finish(Tick end) {
    if (group_open_) settle();
    if (count_ > 0) emitWord(end, true);
    resetWord();
    idle();
}

}  // namespace busdecode
