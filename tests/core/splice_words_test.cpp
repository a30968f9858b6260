// SpliceWords::fields(): every field of a plain struct becomes a word, in order, without
// the struct's fields being listed (a decoder's splice state cannot leave one out).
#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <vector>

#include "core/splice_words.h"

using namespace busdecode;

namespace {

enum class Phase { Idle, Busy };

struct Mixed {
    double period = 2.5;
    bool ma = true, sl = false;
    int count = -3;
    Phase phase = Phase::Busy;
    std::uint64_t data = 0xABCDu;
};

struct Twenty {
    int a0 = 0, a1 = 1, a2 = 2, a3 = 3, a4 = 4, a5 = 5, a6 = 6, a7 = 7, a8 = 8, a9 = 9;
    int b0 = 10, b1 = 11, b2 = 12, b3 = 13, b4 = 14, b5 = 15, b6 = 16, b7 = 17, b8 = 18;
    int b9 = 19;
};

}  // namespace

TEST(SpliceWords, FieldsWritesEveryFieldInOrder) {
    std::vector<std::uint64_t> words;
    SpliceWords(words).fields(Mixed{});
    const std::vector<std::uint64_t> expected{std::bit_cast<std::uint64_t>(2.5), 1, 0,
                                              std::uint64_t(std::int64_t(-3)),   1, 0xABCDu};
    EXPECT_EQ(words, expected);
}

TEST(SpliceWords, FieldsTellsStructsApartByAnyField) {
    std::vector<std::uint64_t> a, b;
    Mixed other;
    other.sl = true;
    SpliceWords(a).fields(Mixed{});
    SpliceWords(b).fields(other);
    EXPECT_NE(a, b);
}

TEST(SpliceWords, FieldsTakesTwentyFields) {
    std::vector<std::uint64_t> words;
    SpliceWords(words).fields(Twenty{});
    ASSERT_EQ(words.size(), 20u);
    for (std::size_t i = 0; i < words.size(); ++i)
        EXPECT_EQ(words[i], i);
}
