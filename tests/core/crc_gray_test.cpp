// Shared mechanics against the published vectors of docs/protocols.md §4.
#include <gtest/gtest.h>

#include <random>

#include "core/crc.h"
#include "core/gray.h"

using namespace busdecode;

TEST(BissCrc6, OfficialAndCapturedVectors) {
    EXPECT_EQ(bissCrc6(0b010011010101, 12), 0x1Cu);                 // V1 AN21
    EXPECT_EQ(bissCrc6((0x05AC53ull << 2) | 0b00, 26), 0b101111u);  // V2 AN18
    EXPECT_EQ(bissCrc6((0x0000000ull << 2) | 0b11, 28), 0x3Au);     // V3
    EXPECT_EQ(bissCrc6((0x3FFFFFFull << 2) | 0b11, 28), 0x22u);     // V4
    EXPECT_EQ(bissCrc6((0x123456ull << 2) | 0b11, 26), 0x35u);      // V5
    EXPECT_EQ(bissCrc6((0x0A5Aull << 2) | 0b10, 15), 0x2Bu);        // V6
    EXPECT_EQ(bissCrc6((0x2AAAAull << 2) | 0b01, 20), 0x2Du);       // V7
    EXPECT_EQ(bissCrc6((0x12345678ull << 2) | 0b00, 34), 0x00u);    // V8
}

TEST(BissCrc16, AN21Vector) {
    BitCrc crc = BitCrc::fromFullPoly(0x190D9, 0, true);
    for (std::uint8_t b : {0xD9, 0xCF, 0xE0, 0xC0, 0xDA})
        crc.pushBits(b, 8);
    EXPECT_EQ(crc.value(), 0x5F29u);
}

TEST(BissCrc4, ControlVectors) {
    EXPECT_EQ(bissCrc4(0b10000000000, 11), 0x6u);
    EXPECT_EQ(bissCrc4(0x48, 8), 0x3u);
    EXPECT_EQ(bissCrc4(0x44, 8), 0x4u);
    EXPECT_EQ(bissCrc4(0x00, 8), 0xFu);
    EXPECT_EQ(bissCrc4((1u << 10) | 0x7E, 11), 0xFu);
}

TEST(BitCrc, FourBitsAtATimeAsOneByOne) {
    // pushBits() takes whole nibbles through a table for CRCs of 4 bits and more; it must
    // agree with push() bit by bit for every width, polynomial, start value and length,
    // including leading bits that do not fill a nibble and registers it runs repeatedly.
    std::mt19937_64 rng(4);
    for (int round = 0; round < 20000; ++round) {
        const int width = 1 + int(rng() % 32);
        const std::uint32_t mask = width == 32 ? 0xFFFFFFFFu : (1u << width) - 1u;
        const std::uint32_t poly = std::uint32_t(rng()) & mask;
        const std::uint32_t init = std::uint32_t(rng()) & mask;
        const std::uint32_t xorout = std::uint32_t(rng()) & mask;
        BitCrc table(width, poly, init, xorout), bitwise(width, poly, init, xorout);
        for (int piece = 0; piece < 3; ++piece) {
            const int n = int(rng() % 65);
            const std::uint64_t bits = rng();
            table.pushBits(bits, n);
            for (int i = n - 1; i >= 0; --i)
                bitwise.push((bits >> i) & 1u);
            ASSERT_EQ(table.value(), bitwise.value())
                << "width " << width << " poly " << poly << " n " << n;
        }
    }
}

TEST(Gray, ReferencePairs) {
    EXPECT_EQ(grayToBinary(0x1000), 0x1FFFu);
    EXPECT_EQ(binaryToGray(0x8000), 0xC000u);
    EXPECT_EQ(grayToBinary(0x2825), 0x3039u);
    EXPECT_EQ(binaryToGray(0x1234), 0x1B2Eu);
    EXPECT_EQ(binaryToGray(0x1579234), 0x1FC5B2Eu);
    for (std::uint64_t v : {0ull, 1ull, 0xFFFFFFFFFFFFFFFFull, 0x8000000000000000ull, 123456789ull})
        EXPECT_EQ(grayToBinary(binaryToGray(v)), v);
}

TEST(FixedLengthCrc, AsBitByBit) {
    // of() looks up one table per byte of the message; it must give what pushing the
    // message bit by bit gives, for every width, polynomial, start value and length up to
    // 128 bits, whatever the bits above the message hold.
    std::mt19937_64 rng(33);
    for (int round = 0; round < 3000; ++round) {
        const int width = 1 + int(rng() % 32);
        const std::uint32_t mask = width == 32 ? 0xFFFFFFFFu : (1u << width) - 1u;
        const BitCrc crc(width, std::uint32_t(rng()) & mask, std::uint32_t(rng()) & mask,
                         std::uint32_t(rng()) & mask);
        const int n = 1 + int(rng() % 128);
        const FixedLengthCrc fixed(crc, n);
        ASSERT_EQ(fixed.length(), n);
        for (int message = 0; message < 8; ++message) {
            const std::uint64_t low = rng(), high = rng();
            BitCrc bitwise = crc;
            bitwise.reset();
            for (int i = n - 1; i >= 0; --i)
                bitwise.push(i >= 64 ? (high >> (i - 64)) & 1u : (low >> i) & 1u);
            ASSERT_EQ(fixed.of(low, high), bitwise.value())
                << "width " << width << " n " << n << " message " << message;
        }
    }
}

TEST(FixedLengthCrc, BissCrc6Vectors) {
    // The published vectors, through the table form BiSS-C's frames use (data, nE, nW).
    const BitCrc crc6 = BitCrc::fromFullPoly(0x43, 0, true);
    EXPECT_EQ(FixedLengthCrc(crc6, 26).of((0x05AC53ull << 2) | 0b00), 0b101111u);  // V2
    EXPECT_EQ(FixedLengthCrc(crc6, 28).of((0x3FFFFFFull << 2) | 0b11), 0x22u);     // V4
    EXPECT_EQ(FixedLengthCrc(crc6, 34).of((0x12345678ull << 2) | 0b00), 0x00u);    // V8
    // Bits above the message are not part of it.
    EXPECT_EQ(FixedLengthCrc(crc6, 15).of(~0ull << 15 | (0x0A5Aull << 2) | 0b10), 0x2Bu);  // V6
}
