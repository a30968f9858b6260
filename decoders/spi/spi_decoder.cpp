#include "spi_decoder.h"

#include <algorithm>
#include <bit>
#include <limits>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include <fmt/format.h>

#include "core/number_text.h"
#include "spi_info.h"

namespace busdecode {

SpiDecoder::SpiDecoder(const Options& o)
    : FastDecoder("spi"),
      cpol_(int(o.integer("cpol"))),
      cpha_(int(o.integer("cpha"))),
      bits_(int(o.integer("bits"))),
      lsb_first_(o.flag("lsb_first")),
      cs_active_high_(o.text("cs_polarity") == "active-high"),
      // Modes 0 and 3 sample on the rising edge, modes 1 and 2 on the falling edge.
      sample_on_rising_(cpol_ == cpha_) {}

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
    std::fill(std::begin(line_of_), std::end(line_of_), -1);
    resetWord();
    probe_.start(lines_.level, bound_ & bit(kSpiCs), cs_active_high_);
}

void SpiDecoder::step(Lines& s, Tick t, int role, bool level) {
    if (unsigned(role) >= unsigned(kSpiRoleCount)) return;
    if (s.open && t > s.tick) settle(s);
    s.level = (s.level & ~bit(role)) | (unsigned(level) << role);
    s.tick = t;
    s.open = true;
}

void SpiDecoder::edge(Tick t, int role, bool level) {
    if (probe_.wants()) probe_.edge(t, role, level);
    step(lines_, t, role, level);
}

// A fast path for the bulk of a busy bus: between chip-select changes only sclk, mosi and
// miso change, and only the sclk edges to the sampling level do anything but keep the
// levels. Sixty-four edges at a time become bit masks (bit i for edge i): which line
// each is on, its level, and whether the next edge is later (the end of its tick group).
// Edges never repeat their line's level (FastDecoder::edges), so a line's level after edge i
// is its level before XOR the parity of its edges up to i, for all 64 edges in a few
// shifts. Then only the sampling clock edges are visited. Everything else (a cs edge, an
// edge of another role, a window the masks cannot describe) goes through step(), and
// the decoder's tests hold the two paths to the same events (spi_block_test.cpp).
namespace {

constexpr int kWindow = 64;

// Bit i of the result: the XOR of bits 0..i of x.
inline std::uint64_t prefixXor(std::uint64_t x) {
    x ^= x << 1;
    x ^= x << 2;
    x ^= x << 4;
    x ^= x << 8;
    x ^= x << 16;
    x ^= x << 32;
    return x;
}

// Bits a..b-1 (0 <= a, b <= 64; none when a >= b). a < 64 whenever a < b, so no shift
// by 64: the sampling loop asks for the bits after edge 63 (fuzz finding).
inline std::uint64_t bitsFrom(int a, int b) {
    if (a >= b) return 0;
    return lowBits(~std::uint64_t(0), b - a) << a;
}

inline int highestBit(std::uint64_t x) {
    return 63 - std::countl_zero(x);
}

}  // namespace

struct SpiDecoder::Window {
    std::uint64_t role[kSpiRoleCount];  // edges on each role's line (line_of_)
    std::uint64_t high;                 // edges to level 1
    std::uint64_t ends;                 // edges followed by a later one
    std::uint64_t slow;                 // edges for step(): cs, or a line of no known role
};

// e[0..64]: 65 edges, the last only for the ends mask. False when the SSE2 masks cannot
// tell the ticks apart (a window spanning 2^24 ticks or more).
bool SpiDecoder::classify(const Edge* e, const int* role_of_line, Window& m) {
#if defined(__SSE2__)
    // Ticks within 2^24 of each other differ in their low 24 bits, which share an edge's
    // low 32-bit half with its line and level.
    if (e[kWindow].t - e[0].t >= (Tick(1) << 24)) return false;
    for (;;) {
        // Each edge's low half: level in bit 0, line in bits 1-7, tick in bits 8-31.
        const auto low = [](const Edge* p) {
            const __m128 x = _mm_castsi128_ps(_mm_loadu_si128(reinterpret_cast<const __m128i*>(p)));
            const __m128 y =
                _mm_castsi128_ps(_mm_loadu_si128(reinterpret_cast<const __m128i*>(p + 2)));
            return _mm_castps_si128(_mm_shuffle_ps(x, y, _MM_SHUFFLE(2, 0, 2, 0)));
        };
        const __m128i tick_bits = _mm_set1_epi32(int(0xFFFFFF00u)), byte = _mm_set1_epi32(0xFF);
        const __m128i line_bits = _mm_set1_epi8(char(0xFE));
        __m128i want[kSpiRoleCount];
        for (int r = 0; r < kSpiRoleCount; ++r)
            want[r] = _mm_set1_epi8(char(line_of_[r] < 0 ? 0xFF : line_of_[r] << 1));
        Window w{};
        for (int k = 0; k < kWindow; k += 16) {
            __m128i same[4], bytes[4];
            for (int j = 0; j < 4; ++j) {
                const __m128i here = low(e + k + 4 * j), next = low(e + k + 4 * j + 1);
                same[j] = _mm_cmpeq_epi32(_mm_and_si128(_mm_xor_si128(here, next), tick_bits),
                                          _mm_setzero_si128());
                bytes[j] = _mm_and_si128(here, byte);
            }
            const __m128i same16 = _mm_packs_epi16(_mm_packs_epi32(same[0], same[1]),
                                                   _mm_packs_epi32(same[2], same[3]));
            const __m128i b = _mm_packus_epi16(_mm_packs_epi32(bytes[0], bytes[1]),
                                               _mm_packs_epi32(bytes[2], bytes[3]));
            const __m128i lines = _mm_and_si128(b, line_bits);
            const auto bits16 = [k](__m128i v) {
                return std::uint64_t(unsigned(_mm_movemask_epi8(v))) << k;
            };
            w.ends |= bits16(same16) ^ (std::uint64_t(0xFFFF) << k);
            w.high |= bits16(_mm_slli_epi16(b, 7));
            for (int r = 0; r < kSpiRoleCount; ++r)
                w.role[r] |= bits16(_mm_cmpeq_epi8(lines, want[r]));
        }
        std::uint64_t known = 0;
        for (int r = 0; r < kSpiRoleCount; ++r)
            known |= w.role[r];
        // An edge of a line not seen before: learn its role once, if it has one.
        bool learnt = false;
        for (std::uint64_t unknown = ~known; unknown; unknown &= unknown - 1) {
            const unsigned line = e[std::countr_zero(unknown)].line;
            const int r = role_of_line[line];
            if (r >= 0 && r < kSpiRoleCount && line_of_[r] < 0) {
                line_of_[r] = int(line);
                learnt = true;
                break;
            }
        }
        if (learnt) continue;
        w.slow = ~known | w.role[kSpiCs];
        m = w;
        return true;
    }
#else
    (void)e;
    (void)role_of_line;
    (void)m;
    return false;
#endif
}

void SpiDecoder::edges(const Edge* first, const Edge* last, const int* role_of_line) {
    // line_of_ holds for this mapping (a caller may pass another between calls).
    for (int r = 0; r < kSpiRoleCount; ++r)
        if (line_of_[r] >= 0 && role_of_line[line_of_[r]] != r)
            std::fill(std::begin(line_of_), std::end(line_of_), -1);
    for (const Edge* e = first; e != last && probe_.wants(); ++e)
        probe_.edge(e->t, role_of_line[e->line], e->level != 0);
    Lines s = lines_;
    Window m;
    for (; last - first > kWindow; first += kWindow) {
        if (!classify(first, role_of_line, m)) {
            steps(s, first, first + kWindow, role_of_line);
            continue;
        }
        // Runs between the slow edges through run(), each slow edge through step().
        for (int a = 0; a < kWindow;) {
            const std::uint64_t slow = m.slow & bitsFrom(a, kWindow);
            const int b = slow ? std::countr_zero(slow) : kWindow;
            if (b > a) run(s, first, m, a, b, role_of_line);
            if (b < kWindow) steps(s, first + b, first + b + 1, role_of_line);
            a = b + 1;
        }
    }
    steps(s, first, last, role_of_line);
    lines_ = s;
}

void SpiDecoder::steps(Lines& s, const Edge* first, const Edge* last, const int* role_of_line) {
    for (; first != last; ++first)
        step(s, first->t, role_of_line[first->line], first->level != 0);
}

// Edges e[a..b): sclk, mosi and miso only, as classify() found.
void SpiDecoder::run(Lines& s, const Edge* e, const Window& m, int a, int b,
                     const int* role_of_line) {
    // Edges at the open group's tick join it through step(); a later one settles it.
    for (; a < b && s.open && e[a].t == s.tick; ++a)
        step(s, e[a].t, role_of_line[e[a].line], e[a].level != 0);
    if (a == b) return;
    if (s.open) settle(s);
    const std::uint64_t in = bitsFrom(a, b);
    const std::uint64_t sclk = m.role[kSpiSclk] & in, mosi = m.role[kSpiMosi] & in,
                        miso = m.role[kSpiMiso] & in;
    const auto levels = [&](std::uint64_t of, int role) {
        return prefixXor(of) ^ ((s.level & bit(role)) ? ~std::uint64_t(0) : 0);
    };
    const std::uint64_t sclk_at = levels(sclk, kSpiSclk), mosi_at = levels(mosi, kSpiMosi),
                        miso_at = levels(miso, kSpiMiso);
    if (((sclk_at ^ m.high) & sclk) | ((mosi_at ^ m.high) & mosi) | ((miso_at ^ m.high) & miso)) {
        // A level repeated (not from a session): the masks' parity does not hold.
        steps(s, e + a, e + b, role_of_line);
        return;
    }
    // Groups that end inside the run (the next edge, in it or after it, is later).
    const std::uint64_t ends = m.ends & in;
    if (!(bound_ & bit(kSpiCs)) || csActive(s.level))
        sampleRun(e, sclk & (sample_on_rising_ ? m.high : ~m.high), sclk, ends, a, mosi_at,
                  miso_at);
    const auto levelsAt = [&](int i) {
        return (s.level & ~(bit(kSpiSclk) | bit(kSpiMosi) | bit(kSpiMiso))) |
               unsigned((sclk_at >> i) & 1) << kSpiSclk | unsigned((mosi_at >> i) & 1) << kSpiMosi |
               unsigned((miso_at >> i) & 1) << kSpiMiso;
    };
    s.settled = ends ? levelsAt(highestBit(ends)) : s.level;
    s.level = levelsAt(b - 1);
    s.tick = e[b - 1].t;
    s.open = true;
}

// The samples of run(): a group samples when its last sclk edge goes to the sampling
// level (`to`: those sclk edges) and it holds an odd number of sclk edges (sclk changed
// across it). The word in progress is kept in registers here: through sampleBit(), each
// sample waited for the stores of the one before (count, bits and times).
void SpiDecoder::sampleRun(const Edge* e, std::uint64_t to, std::uint64_t sclk, std::uint64_t ends,
                           int a, std::uint64_t mosi_at, std::uint64_t miso_at) {
    const std::uint64_t parity = prefixXor(sclk);
    // Nearly every group is one edge: an edge that ends its group, after an edge that
    // ended the one before (or first in the run, the open group settled).
    const std::uint64_t alone = ends & ((ends << 1) | (std::uint64_t(1) << a));
    Word w = word_;
    for (; to; to &= to - 1) {
        const int i = std::countr_zero(to);
        int g = i;  // the group's last edge
        if (!((alone >> i) & 1)) {
            const std::uint64_t later = ends >> i;
            if (!later) break;  // in the open group
            g = i + std::countr_zero(later);
            if (sclk & bitsFrom(i + 1, g + 1)) continue;  // not the group's last sclk edge
            const std::uint64_t before = ends & bitsFrom(0, i);
            const int first = before ? highestBit(before) + 1 : a;
            if (!(((parity >> i) ^ (first > 0 ? parity >> (first - 1) : 0)) & 1)) continue;
        }
        const Tick t = e[g].t;
        if (takeBit(w, t,
                    unsigned((mosi_at >> g) & 1) << kSpiMosi | unsigned((miso_at >> g) & 1)
                                                                   << kSpiMiso)) {
            word_ = w;
            wordDone(t);
            w = word_;
        }
    }
    word_ = w;
}

Tick SpiDecoder::watermark(Tick now) const {
    if (word_.count > 0) return word_.start;
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
        if (word_.count > 0 && csActive(s.settled)) emitWord(t, true);
        resetWord();
    }
    const bool sampling =
        (changed & bit(kSpiSclk)) && bool(s.level & bit(kSpiSclk)) == sample_on_rising_;
    s.settled = s.level;
    if (sampling && (!(bound_ & bit(kSpiCs)) || csActive(s.level))) sampleBit(t, s.level);
}

bool SpiDecoder::takeBit(Word& w, Tick t, unsigned level) const {
    if (w.count == 0) {
        w.start = t;
        w.prev_sample = t;
    } else {
        w.prev_sample = w.last_sample;
    }
    w.last_sample = t;
    if (bound_ & bit(kSpiMosi))
        w.mosi = BitWord::pushed(w.mosi, w.count, level & bit(kSpiMosi), lsb_first_);
    if (bound_ & bit(kSpiMiso))
        w.miso = BitWord::pushed(w.miso, w.count, level & bit(kSpiMiso), lsb_first_);
    return ++w.count == bits_;
}

void SpiDecoder::sampleBit(Tick t, unsigned level) {
    if (takeBit(word_, t, level)) wordDone(t);
}

void SpiDecoder::wordDone(Tick t) {
    // sigrok's end estimate: one bit period (the last sample interval) after the last bit.
    // Saturated: an absurd gap before the last bit must not overflow (fuzz finding;
    // period >= 0 as edges come in time order, so max - period cannot overflow).
    const Tick period = t - word_.prev_sample;
    emitWord(t > std::numeric_limits<Tick>::max() - period ? std::numeric_limits<Tick>::max()
                                                           : t + period,
             false);
    resetWord();
}

void SpiDecoder::emitWord(Tick end, bool short_frame) {
    ++words_;
    if (short_frame)
        short_bits_ = ++short_words_ == 1 || short_bits_ == word_.count ? word_.count : -1;
    EventPtr owned = newEvent("transfer", word_.start, std::max(end, word_.start));
    Event& e = *owned;
    const int n = word_.count;
    const int digits = (n + 3) / 4;
    ShortLine text;  // at most 64 bits: "MOSI 0x" + 16 digits, twice, and the short note
    bool first = true;
    // Fields only when a sink or another decoder reads them: text output prints the
    // summary alone, jsonl and the other sinks the fields alone.
    const bool fields = fieldsWanted();
    const bool summary = summariesWanted();
    auto put = [&](const char* key, const char* label, std::uint64_t w, bool bound) {
        if (!bound) {
            if (fields) e.add(key, Null{});
            return;
        }
        // MSB-first words keep the newest 64 bits; LSB-first words the first 64.
        std::uint64_t v = lowBits(w, n);
        if (fields) e.add(key, v);
        if (!summary) return;
        if (!first) text.text(" ");
        first = false;
        text.text(label).text(" 0x").hex(v, digits);
    };
    put("mosi", "MOSI", word_.mosi, bound_ & bit(kSpiMosi));
    put("miso", "MISO", word_.miso, bound_ & bit(kSpiMiso));
    if (fields) e.add("bits", std::int64_t(n));
    if (short_frame) {
        e.error("short_frame");
        if (summary) text.text(" (").dec(n).text(" of ").dec(bits_).text(" bits)");
    }
    if (word_glitch_) e.error("glitch");
    if (summary) e.summary.assign(text.view());
    emit(std::move(owned));
}

void SpiDecoder::resetWord() {
    word_.mosi = word_.miso = 0;
    word_.count = 0;
    word_glitch_ = false;
}

void SpiDecoder::glitch(Tick t, int role) {
    (void)t;
    // A removed pulse on a line of the word in progress makes that word doubtful.
    if (role == kSpiSclk || role == kSpiMosi || role == kSpiMiso || role == kSpiCs)
        if (word_.count > 0) word_glitch_ = true;
}

void SpiDecoder::finish(Tick end) {
    if (lines_.open) settle(lines_);
    if (word_.count > 0) emitWord(end, true);
    resetWord();
}

std::optional<std::string> SpiDecoder::modeHint() const {
    const auto f = probe_.finding();
    if (!f || f->sample_rising == sample_on_rising_) return std::nullopt;
    // The clock's rest level picks between the two modes that sample on that edge.
    const int cpol = f->cpol.value_or(cpol_);
    const int cpha = f->sample_rising == (cpol == 0) ? 0 : 1;
    return fmt::format(
        "the data lines change after the {} clock edges ({} of {} changes){}: the traffic "
        "looks SPI mode {} (--opt cpol={} --opt cpha={}), which samples on the {} edge, "
        "not cpol={} cpha={}",
        f->sample_rising ? "falling" : "rising", f->agreeing, f->changes,
        f->cpol ? fmt::format(" and the clock rests {} at chip select", cpol ? "high" : "low") : "",
        cpol * 2 + cpha, cpol, cpha, f->sample_rising ? "rising" : "falling", cpol_, cpha_);
}

std::vector<std::string> SpiDecoder::advice() const {
    if (auto hint = modeHint()) return {*hint};
    // A master that stops now and then cuts a few words short; half of them or more, each
    // after the same count, are words of that length.
    if (words_ < 2 || short_words_ * 2 < words_ || short_bits_ <= 0) return {};
    return {fmt::format(
        "{} of {} words were cut short by chip select, each after {} bits of bits={}: the "
        "words look {} bits long (--opt bits={})",
        short_words_, words_, short_bits_, bits_, short_bits_, short_bits_)};
}

}  // namespace busdecode
