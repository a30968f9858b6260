#pragma once
// Bit-serial CRC, MSB first, as BiSS (CRC6 0x43, CRC4 0x13, CRC16 0x190D9) and most
// serial encoder protocols define it: the input is a bit string, not bytes.
#include <cstddef>
#include <cstdint>

namespace busdecode {

class BitCrc {
public:
    // width 1..32; poly without the top bit (CRC6 x^6+x+1 -> 0x03); init and xorout
    // applied as in the CRC catalogue (refin = refout = false).
    BitCrc(int width, std::uint32_t poly, std::uint32_t init = 0, std::uint32_t xorout = 0)
        : width_(width), poly_(poly), init_(init), xorout_(xorout), reg_(init) {}

    void reset() { reg_ = init_; }
    void push(bool bit) {
        const std::uint32_t top = (reg_ >> (width_ - 1)) & 1u;
        reg_ = (reg_ << 1) & mask();
        if (top ^ (bit ? 1u : 0u)) reg_ ^= poly_;
    }
    // Pushes the low `n` bits of `bits`, most significant first.
    void pushBits(std::uint64_t bits, int n) {
        for (int i = n - 1; i >= 0; --i)
            push((bits >> i) & 1u);
    }
    std::uint32_t value() const { return (reg_ ^ xorout_) & mask(); }
    int width() const { return width_; }

    // Builds from a polynomial written with its top bit (0x43 for CRC6, 0x13 for CRC4,
    // 0x190D9 for CRC16): the form users find in datasheets.
    static BitCrc fromFullPoly(std::uint32_t full_poly, std::uint32_t init = 0,
                               bool inverted = true);

private:
    std::uint32_t mask() const { return width_ >= 32 ? 0xFFFFFFFFu : ((1u << width_) - 1u); }
    int width_;
    std::uint32_t poly_, init_, xorout_, reg_;
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
