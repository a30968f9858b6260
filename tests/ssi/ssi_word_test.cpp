// The word rules against the vectors of docs/protocols.md §4.5 and the vendor notes:
// bit assembly, ring shift, fields, Gray, parity, status bits, option checks.
#include <gtest/gtest.h>

#include <cmath>

#include "core/gray.h"
#include "core/options.h"
#include "ssi_config.h"
#include "ssi_word.h"

using namespace busdecode;

namespace {

SsiConfig config(std::map<std::string, std::string> given) {
    return SsiConfig::fromOptions(Options::resolve(ssiInfo(), given));
}

std::vector<std::uint8_t> bitsOf(const std::string& s) {
    std::vector<std::uint8_t> out;
    for (char c : s)
        if (c == '0' || c == '1') out.push_back(c == '1');
    return out;
}

}  // namespace

TEST(SsiWord, V30Binary13Bits) {
    auto cfg = config({{"bits", "13"}, {"st_bits", "13"}});
    // Falling-edge samples f1..f14 = 11001000110100: f1 (idle 1) is no bit with lead=0.
    auto s = bitsOf("11001000110100");
    s.erase(s.begin());
    const SsiWord w = assembleWord(s, cfg);
    EXPECT_EQ(w.raw, 0x1234u);
    EXPECT_EQ(w.bits, 13);
    EXPECT_FALSE(w.short_frame);
    EXPECT_EQ(w.repeats, 1);
    EXPECT_EQ(splitFields(w.raw, cfg).st, 0x1234u);
}

TEST(SsiWord, V31Gray13Bits) {
    auto cfg = config({{"bits", "13"}, {"st_bits", "13"}, {"gray", "1"}});
    const SsiWord w = assembleWord(bitsOf("1101100101110"), cfg);
    EXPECT_EQ(w.raw, 0x1B2Eu);
    const SsiFields f = splitFields(w.raw, cfg);
    EXPECT_EQ(f.position, 0x1234u);
    EXPECT_NEAR(*f.angle, 360.0 * 0x1234 / 8192.0, 1e-9);
}

TEST(SsiWord, V32Gray25BitsMultiTurn) {
    auto cfg = config({{"bits", "25"}, {"st_bits", "13"}, {"mt_bits", "12"}, {"gray", "1"}});
    const SsiWord w = assembleWord(bitsOf("1111111000101101100101110"), cfg);
    EXPECT_EQ(w.raw, 0x1FC5B2Eu);
    const SsiFields f = splitFields(w.raw, cfg);
    EXPECT_EQ(f.position, 0x1579234u);
    EXPECT_EQ(f.mt, 0xABCu);
    EXPECT_EQ(f.st, 0x1234u);
}

TEST(SsiWord, V33EvenParityAfterLsb) {
    auto cfg = config({{"bits", "14"}, {"st_bits", "13"}, {"parity", "even"}});
    EXPECT_EQ(cfg.pos_shift, 1);  // auto: the parity bit sits below the position
    const SsiWord w = assembleWord(bitsOf("1001000110100 1"), cfg);
    SsiFields f = splitFields(w.raw, cfg);
    EXPECT_EQ(f.st, 0x1234u);
    ASSERT_TRUE(f.parity_ok.has_value());
    EXPECT_TRUE(*f.parity_ok);
    f = splitFields(w.raw ^ 1, cfg);  // parity bit flipped
    EXPECT_FALSE(*f.parity_ok);
    auto odd = config({{"bits", "14"}, {"st_bits", "13"}, {"parity", "odd"}});
    EXPECT_FALSE(*splitFields(w.raw, odd).parity_ok);
    EXPECT_TRUE(*splitFields(w.raw ^ 1, odd).parity_ok);
    auto msb =
        config({{"bits", "14"}, {"st_bits", "13"}, {"parity", "even"}, {"parity_pos", "msb"}});
    EXPECT_EQ(msb.pos_shift, 0);
}

TEST(SsiWord, V34DoubleTransmission) {
    auto cfg = config({{"bits", "13"}, {"st_bits", "13"}});
    // 2 x (n+1) clocks: samples f2..f28 = word 0 word (the last 0 comes after the last clock).
    const SsiWord w = assembleWord(bitsOf("1001000110100 0 1001000110100"), cfg);
    EXPECT_EQ(w.raw, 0x1234u);
    EXPECT_EQ(w.repeats, 2);
    EXPECT_TRUE(w.repeat_match);
    EXPECT_TRUE(w.separator_ok);
    EXPECT_EQ(w.partial_bits, 0);
}

TEST(SsiWord, RepeatMismatchNamesTheBits) {
    auto cfg = config({{"bits", "13"}, {"st_bits", "13"}});
    // Third transmission: the MSB (bit 12) and bit 2 differ.
    const SsiWord w = assembleWord(bitsOf("1001000110100 0 1001000110100 0 0001000110000"), cfg);
    EXPECT_EQ(w.repeats, 3);
    EXPECT_FALSE(w.repeat_match);
    EXPECT_EQ(w.diff_bits, (std::vector<std::int64_t>{2, 12}));
}

TEST(SsiWord, PartialRepeatAndSeparator) {
    auto cfg = config({{"bits", "13"}, {"st_bits", "13"}});
    // An SPI-style read of 20 bits: word, separator, 6 bits of the repeat.
    SsiWord w = assembleWord(bitsOf("1001000110100 0 100100"), cfg);
    EXPECT_EQ(w.repeats, 1);
    EXPECT_EQ(w.partial_bits, 6);
    EXPECT_TRUE(w.repeat_match);
    w = assembleWord(bitsOf("1001000110100 0 100110"), cfg);
    EXPECT_FALSE(w.repeat_match);
    EXPECT_EQ(w.diff_bits, (std::vector<std::int64_t>{8}));
    w = assembleWord(bitsOf("1001000110100 1 1001000110100"), cfg);
    EXPECT_FALSE(w.separator_ok);
    EXPECT_TRUE(w.repeat_match);
    auto gap3 = config({{"bits", "13"}, {"st_bits", "13"}, {"ring_gap", "3"}});
    w = assembleWord(bitsOf("1001000110100 000 1001000110100"), gap3);
    EXPECT_EQ(w.repeats, 2);
    EXPECT_TRUE(w.repeat_match);
    EXPECT_TRUE(w.separator_ok);
}

TEST(SsiWord, ShortFrameKeepsItsBits) {
    auto cfg = config({{"bits", "13"}, {"st_bits", "13"}});
    const SsiWord w = assembleWord(bitsOf("1001000"), cfg);
    EXPECT_TRUE(w.short_frame);
    EXPECT_EQ(w.bits, 7);
    EXPECT_EQ(w.raw, 0b1001000u);
    EXPECT_EQ(w.repeats, 0);
}

TEST(SsiWord, PositalLeadBitExample) {
    // POSITAL: 25 samples starting at the first falling edge (the idle 1 is the lead bit),
    // 12-bit MT and 12-bit ST: 0x010014ED -> MT 1, ST 0x4ED, 110.83 degrees.
    auto cfg = config({{"bits", "25"}, {"lead", "1"}, {"mt_bits", "12"}, {"st_bits", "12"}});
    std::vector<std::uint8_t> s;
    for (int b = 24; b >= 0; --b)
        s.push_back(0x010014ED >> b & 1);
    const SsiWord w = assembleWord(s, cfg);
    EXPECT_EQ(w.raw, 0x010014EDu);
    const SsiFields f = splitFields(w.raw, cfg);
    EXPECT_EQ(f.mt, 1u);
    EXPECT_EQ(f.st, 0x4EDu);
    EXPECT_EQ(std::round(*f.angle * 100) / 100, 110.83);
    EXPECT_EQ(f.status, 1u);  // the lead bit
    // Ring shift after a lead bit: separator, then the 24 data bits again.
    s.push_back(0);
    for (int b = 23; b >= 0; --b)
        s.push_back(0x0014ED >> b & 1);
    const SsiWord r = assembleWord(s, cfg);
    EXPECT_EQ(r.repeats, 2);
    EXPECT_TRUE(r.repeat_match);
}

TEST(SsiWord, Tmc8100StatusBits) {
    // TMC8100 demo: 25 bits, bits 23/22 diagnostic, 16-bit Gray position.
    auto cfg = config({{"bits", "25"},
                       {"st_bits", "16"},
                       {"gray", "1"},
                       {"status_bits", "out_of_range@23, low_quality@22"}});
    ASSERT_EQ(cfg.status.size(), 2u);
    EXPECT_EQ(cfg.status[0].name, "out_of_range");
    EXPECT_EQ(cfg.status[0].bit, 23);
    const std::uint64_t raw = (1u << 22) | binaryToGray(0x8000);
    const SsiFields f = splitFields(raw, cfg);
    EXPECT_EQ(f.st, 0x8000u);
    EXPECT_DOUBLE_EQ(*f.angle, 180.0);
    EXPECT_EQ(f.status, 0x40u);  // bits 16..24 of raw
    // Plain names count up from the first bit above the position; empty names skip.
    auto seq = config(
        {{"bits", "25"}, {"st_bits", "16"}, {"status_bits", ",,,,,,low_quality,out_of_range"}});
    ASSERT_EQ(seq.status.size(), 2u);
    EXPECT_EQ(seq.status[0].bit, 22);
    EXPECT_EQ(seq.status[1].bit, 23);
}

TEST(SsiWord, LsbFirstWord) {
    auto cfg = config({{"bits", "8"}, {"st_bits", "8"}, {"lsb_first", "1"}});
    const SsiWord w = assembleWord(bitsOf("10110000"), cfg);
    EXPECT_EQ(w.raw, 0x0Du);
    EXPECT_EQ(cfg.bitIndex(0), 0);
}

TEST(SsiConfig, RejectsContradictions) {
    EXPECT_THROW(config({{"bits", "13"}, {"st_bits", "13"}, {"mt_bits", "1"}}), InputError);
    EXPECT_THROW(config({{"bits", "25"}, {"status_bits", "a@25"}}), InputError);
    EXPECT_THROW(config({{"bits", "25"}, {"status_bits", "a b"}}), InputError);
    EXPECT_THROW(config({{"bits", "25"}, {"status_bits", "a@1,a@2"}}), InputError);
    EXPECT_THROW(config({{"bits", "25"}, {"clock_min_hz", "3e6"}}), InputError);
    EXPECT_THROW(config({{"sample_edge", "both"}}), InputError);
    EXPECT_THROW(config({{"bits", "65"}}), InputError);
    const SsiConfig c = config({{"tm_us", "30"}, {"status_bits", "raw@24"}});
    EXPECT_DOUBLE_EQ(c.tm_min_us, 15);
    EXPECT_DOUBLE_EQ(c.tm_max_us, 60);
    EXPECT_EQ(c.status[0].name, "status_raw");  // never shadows a contract field
}
