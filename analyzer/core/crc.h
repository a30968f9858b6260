#pragma once
// Bit-serial CRC, MSB first, as BiSS (CRC6 0x43, CRC4 0x13, CRC16 0x190D9) and most
// serial encoder protocols define it: the input is a bit string, not bytes.
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace busdecode {

class BitCrc {
public:
    // width 1..32; poly without the top bit (CRC6 x^6+x+1 -> 0x03); init and xorout
    // applied as in the CRC catalogue (refin = refout = false).
    BitCrc(int width, std::uint32_t poly, std::uint32_t init = 0, std::uint32_t xorout = 0)
        : width_(width), poly_(poly), init_(init), xorout_(xorout), reg_(init) {
        buildNibbleTable();
    }

    void reset() { reg_ = init_; }
    void push(bool bit) {
        const std::uint32_t top = (reg_ >> (width_ - 1)) & 1u;
        reg_ = (reg_ << 1) & mask();
        if (top ^ (bit ? 1u : 0u)) reg_ ^= poly_;
    }
    // Pushes the low `n` bits of `bits`, most significant first: four at a time through
    // a table when the CRC is that wide (a BiSS-C position takes a quarter of the steps).
    void pushBits(std::uint64_t bits, int n) {
        int i = n;
        if (width_ >= 4) {
            for (; i % 4 != 0; --i)  // the leading bits, so that whole nibbles are left
                push((bits >> (i - 1)) & 1u);
            for (; i > 0; i -= 4) {
                // Only the register's top four bits and the four data bits decide what is
                // fed back in four steps; the CRC is linear, so the table holds it.
                const std::uint32_t top = (reg_ >> (width_ - 4)) ^ std::uint32_t(bits >> (i - 4));
                reg_ = ((reg_ << 4) & mask()) ^ nibble_[top & 0xF];
            }
        }
        for (; i > 0; --i)
            push((bits >> (i - 1)) & 1u);
    }
    std::uint32_t value() const { return (reg_ ^ xorout_) & mask(); }
    int width() const { return width_; }

    // Builds from a polynomial written with its top bit (0x43 for CRC6, 0x13 for CRC4,
    // 0x190D9 for CRC16): the form users find in datasheets.
    static BitCrc fromFullPoly(std::uint32_t full_poly, std::uint32_t init = 0,
                               bool inverted = true);

private:
    std::uint32_t mask() const { return width_ >= 32 ? 0xFFFFFFFFu : ((1u << width_) - 1u); }
    // nibble_[t]: the register after four zero bits pushed from t in its top four bits
    // (worked out with push() itself, from the constructor, before reg_ is used).
    void buildNibbleTable() {
        if (width_ < 4) return;
        for (std::uint32_t t = 0; t < 16; ++t) {
            reg_ = t << (width_ - 4);
            for (int k = 0; k < 4; ++k)
                push(false);
            nibble_[t] = reg_;
        }
        reg_ = init_;
    }
    int width_;
    std::uint32_t poly_, init_, xorout_, reg_;
    std::uint32_t nibble_[16] = {};
};

// The CRC of messages of one length n (1..128 bits), a frame's worth, set by a decoder's
// options (BiSS-C: the data, nE and nW). The CRC is affine in the message's bits, so a
// message's CRC is the all-zero message's XOR one table entry per byte of the message:
// independent look-ups, where BitCrc::pushBits() chains every step on the one before
// (about 130 instructions fewer per BiSS-C frame by callgrind).
class FixedLengthCrc {
public:
    // The same CRC as `crc` (polynomial, init, xorout; its register is not used).
    FixedLengthCrc(const BitCrc& crc, int n);

    // = crc.reset(), then pushing the message's n bits, MSB first, then crc.value(). The
    // message is `high`'s low n - 64 bits then `low`'s 64 (n > 64), or `low`'s low n bits.
    // Bits above the message's are ignored.
    std::uint32_t of(std::uint64_t low, std::uint64_t high = 0) const {
        std::uint32_t v = zero_;
        const int low_bytes = bytes_ < 8 ? bytes_ : 8;
        for (int j = 0; j < low_bytes; ++j)
            v ^= tables_[std::size_t(j)][(low >> (8 * j)) & 0xFF];
        for (int j = 8; j < bytes_; ++j)
            v ^= tables_[std::size_t(j)][(high >> (8 * (j - 8))) & 0xFF];
        return v;
    }
    int length() const { return n_; }

private:
    int n_;
    int bytes_;           // tables in use: one per byte of the message, from its low end
    std::uint32_t zero_;  // the CRC of n zero bits
    // tables_[j][b]: what byte j (bits 8j..8j+7 from the end) holding b adds, beyond
    // zero_; entries for bits past the message's are 0 (ignored bits).
    std::vector<std::array<std::uint32_t, 256>> tables_;
};

// One-shot helper over the low n bits of `bits` (MSB first).
std::uint32_t crcOfBits(std::uint64_t bits, int n, int width, std::uint32_t poly,
                        std::uint32_t init, std::uint32_t xorout);

// BiSS conventions: CRC6 poly 0x43 and CRC4 poly 0x13, init 0, sent inverted.
inline std::uint32_t bissCrc6(std::uint64_t bits, int n) {
    return crcOfBits(bits, n, 6, 0x03, 0, 0x3F);
}
inline std::uint32_t bissCrc4(std::uint64_t bits, int n) {
    return crcOfBits(bits, n, 4, 0x03, 0, 0x0F);
}

}  // namespace busdecode
