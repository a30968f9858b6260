#include "spi_decoder.h"

#include <limits>

#include <fmt/format.h>

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
    bound_ = 0;
    lines_ = Lines{};
    for (int r = 0; r < kSpiRoleCount; ++r) {
        int lv = r < int(ctx.initial_levels.size()) ? ctx.initial_levels[r] : -1;
        if (lv >= 0) bound_ |= bit(r);
        if (lv == 1) lines_.level |= bit(r);
    }
    lines_.settled = lines_.level;
    resetWord();
}

void SpiDecoder::step(Lines& s, Tick t, int role, bool level) {
    if (unsigned(role) >= unsigned(kSpiRoleCount)) return;
    if (s.open && t > s.tick) settle(s);
    s.level = (s.level & ~bit(role)) | (unsigned(level) << role);
    s.tick = t;
    s.open = true;
}

void SpiDecoder::edge(Tick t, int role, bool level) {
    step(lines_, t, role, level);
}

void SpiDecoder::edges(const Edge* first, const Edge* last, const int* role_of_line) {
    Lines s = lines_;
    for (; first != last; ++first)
        step(s, first->t, role_of_line[first->line], first->level != 0);
    lines_ = s;
}

Tick SpiDecoder::watermark(Tick now) const {
    if (count_ > 0) return word_start_;
    return lines_.open ? lines_.tick : now;
}

void SpiDecoder::advance(Tick now) {
    if (lines_.open && now > lines_.tick) settle(lines_);
}

void SpiDecoder::settle(Lines& s) {
    s.open = false;
    const Tick t = s.tick;
    const unsigned changed = s.level ^ s.settled;
    if (changed & bound_ & bit(kSpiCs)) {
        // Any cs change ends the word in progress (sigrok resets its state likewise).
        if (count_ > 0 && csActive(s.settled)) emitWord(t, true);
        resetWord();
    }
    const bool sampling =
        (changed & bit(kSpiSclk)) && bool(s.level & bit(kSpiSclk)) == sample_on_rising_;
    s.settled = s.level;
    if (sampling && (!(bound_ & bit(kSpiCs)) || csActive(s.level))) sampleBit(t, s.level);
}

void SpiDecoder::sampleBit(Tick t, unsigned level) {
    if (count_ == 0) {
        word_start_ = t;
        prev_sample_ = t;
    } else {
        prev_sample_ = last_sample_;
    }
    last_sample_ = t;
    if (bound_ & bit(kSpiMosi)) mosi_.push(level & bit(kSpiMosi));
    if (bound_ & bit(kSpiMiso)) miso_.push(level & bit(kSpiMiso));
    if (++count_ == bits_) wordDone(t);
}

void SpiDecoder::wordDone(Tick t) {
    // sigrok's end estimate: one bit period (the last sample interval) after the last bit.
    // Saturated: an absurd gap before the last bit must not overflow (fuzz finding;
    // period >= 0 as edges come in time order, so max - period cannot overflow).
    const Tick period = t - prev_sample_;
    emitWord(t > std::numeric_limits<Tick>::max() - period ? std::numeric_limits<Tick>::max()
                                                           : t + period,
             false);
    resetWord();
}

void SpiDecoder::emitWord(Tick end, bool short_frame) {
    ++words_;
    if (short_frame) short_bits_ = ++short_words_ == 1 || short_bits_ == count_ ? count_ : -1;
    EventPtr owned = freshEvent();
    Event& e = *owned;
    e.proto = "spi";
    e.type = "transfer";
    e.start = word_start_;
    e.end = std::max(end, word_start_);
    const int n = count_;
    const int digits = (n + 3) / 4;
    ShortLine text;  // at most 64 bits: "MOSI 0x" + 16 digits, twice, and the short note
    bool first = true;
    // Fields only when a sink or another decoder reads them: text output prints the
    // summary alone (bench/README.md, stop 23).
    const bool fields = fieldsWanted();
    auto put = [&](const char* key, const char* label, const BitWord& w, bool bound) {
        if (!bound) {
            if (fields) e.add(key, Null{});
            return;
        }
        // MSB-first words keep the newest 64 bits; LSB-first words the first 64.
        std::uint64_t v = lowBits(w.value(), n);
        if (fields) e.add(key, v);
        if (!first) text.text(" ");
        first = false;
        text.text(label).text(" 0x").hex(v, digits);
    };
    put("mosi", "MOSI", mosi_, bound_ & bit(kSpiMosi));
    put("miso", "MISO", miso_, bound_ & bit(kSpiMiso));
    if (fields) e.add("bits", std::int64_t(n));
    if (short_frame) {
        e.error("short_frame");
        text.text(" (").dec(n).text(" of ").dec(bits_).text(" bits)");
    }
    if (word_glitch_) e.error("glitch");
    e.summary.assign(text.view());
    emit(std::move(owned));
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
    if (lines_.open) settle(lines_);
    if (count_ > 0) emitWord(end, true);
    resetWord();
}

std::vector<std::string> SpiDecoder::advice() const {
    // A master that stops now and then cuts a few words short; half of them or more, each
    // after the same count, are words of that length.
    if (words_ < 2 || short_words_ * 2 < words_ || short_bits_ <= 0) return {};
    return {fmt::format(
        "{} of {} words were cut short by chip select, each after {} bits of bits={}: the "
        "words look {} bits long (--opt bits={})",
        short_words_, words_, short_bits_, bits_, short_bits_, short_bits_)};
}

}  // namespace busdecode
