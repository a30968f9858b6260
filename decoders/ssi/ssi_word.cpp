#include "ssi_word.h"

#include <bit>
#include <cmath>

#include "core/bit_word.h"
#include "core/gray.h"

namespace busdecode {

std::vector<std::int64_t> bitList(std::uint64_t diff) {
    std::vector<std::int64_t> out;
    for (int b = 0; b < 64; ++b)
        if (diff >> b & 1) out.push_back(b);
    return out;
}

SsiWord assembleWord(const std::vector<std::uint8_t>& samples, const SsiConfig& cfg) {
    SsiWord w;
    const int n = int(samples.size());
    BitWord word(cfg.lsb_first);
    for (int i = 0; i < n && i < cfg.bits; ++i)
        word.push(samples[i] != 0);
    w.raw = word.value();
    w.bits = word.count();
    if (w.bits < cfg.bits) {
        w.short_frame = true;
        return w;
    }
    w.repeats = 1;

    // Ring shift: after the first word (lead bit included) come `ring_gap` zeros, then the
    // encoder's data bits again, and so on while the master keeps clocking.
    const int data = cfg.dataBits();
    const int lead = cfg.lead ? 1 : 0;
    std::uint64_t diff = 0;
    int pos = cfg.bits;
    while (pos < n) {
        for (int g = 0; g < cfg.ring_gap && pos < n; ++g, ++pos)
            if (samples[pos]) w.separator_ok = false;
        int got = 0;
        for (; got < data && pos < n; ++got, ++pos) {
            const int i = lead + got;  // the matching bit of the first word, in wire order
            if (samples[pos] != samples[i]) diff |= std::uint64_t(1) << cfg.bitIndex(i);
        }
        if (got == data) {
            ++w.repeats;
        } else {
            w.partial_bits = got;
        }
    }
    w.repeat_match = diff == 0;
    w.diff_bits = bitList(diff);
    return w;
}

namespace {

bool repeatsEvery(const std::vector<std::uint8_t>& samples, int n, int gap) {
    const int size = int(samples.size());
    for (int pos = n; pos < size;) {
        for (int g = 0; g < gap && pos < size; ++g, ++pos)
            if (samples[std::size_t(pos)]) return false;
        for (int i = 0; i < n && pos < size; ++i, ++pos)
            if (samples[std::size_t(pos)] != samples[std::size_t(i)]) return false;
    }
    return true;
}

}  // namespace

int ringWidth(const std::vector<std::uint8_t>& samples, int ring_gap) {
    constexpr int kMinCompared = 8;  // a chance match of fewer bits is too likely
    const int size = int(samples.size());
    bool any_one = false;
    for (int n = 1; n + ring_gap + kMinCompared <= size; ++n) {
        any_one = any_one || samples[std::size_t(n - 1)];
        if (any_one && repeatsEvery(samples, n, ring_gap)) return n;
    }
    return 0;
}

SsiFields splitFields(std::uint64_t raw, const SsiConfig& cfg) {
    SsiFields f;
    const int pos_bits = cfg.st_bits + cfg.mt_bits;
    std::uint64_t pos = lowBits(raw >> cfg.pos_shift, pos_bits);
    if (cfg.gray) pos = grayToBinary(pos);
    f.position = pos;
    f.st = lowBits(pos, cfg.st_bits);
    f.mt = cfg.st_bits >= 64 ? 0 : lowBits(pos >> cfg.st_bits, cfg.mt_bits);
    if (cfg.st_bits > 0) f.angle = 360.0 * double(f.st) / std::ldexp(1.0, cfg.st_bits);
    const int above = cfg.pos_shift + pos_bits;
    f.status = above >= 64 ? 0 : lowBits(raw >> above, cfg.bits - above);
    if (cfg.parity != SsiParity::None) {
        const int ones = std::popcount(lowBits(raw, cfg.bits));
        f.parity_ok = (ones % 2 == 0) == (cfg.parity == SsiParity::Even);
    }
    return f;
}

}  // namespace busdecode
