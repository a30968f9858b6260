// The fuzz targets of the new formats (dsl, compressed, sample_rows, saleae_bin, fst) run
// on their seeds and on cut and mutated copies of them, through the same harness the
// libFuzzer targets use: every input either reads or ends in one InputError naming the
// file, under the CI's sanitizers too.
#include <gtest/gtest.h>

#include <filesystem>
#include <random>

#include "fuzz_harness.h"
#include "support/paths.h"

namespace busdecode::test {
namespace {

// `mutate`: also bytes changed at random (not for FST: fstapi trusts the contents of
// its compressed blocks, see the Fst test).
void runAll(const std::string& target, bool mutate = true) {
    const auto dir = std::filesystem::path(sourceDir()) / "fuzz/seeds" / target;
    std::mt19937 rng(1);
    int inputs = 0;
    for (const auto& e : std::filesystem::directory_iterator(dir)) {
        const std::string seed = readFile(e.path().string());
        auto run = [&](const std::string& bytes) {
            ++inputs;
            ASSERT_NO_THROW(fuzz::runTarget(
                target, reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()))
                << target << " " << e.path();
        };
        run(seed);
        for (std::size_t cut = 0; cut < seed.size();
             cut += mutate ? std::max<std::size_t>(1, seed.size() / 24) : 1)
            run(seed.substr(0, cut));
        for (int m = 0; mutate && m < 150 && !seed.empty(); ++m) {
            std::string bytes = seed;
            for (int k = 0; k < 1 + int(rng() % 4); ++k)
                bytes[rng() % bytes.size()] = char(rng());
            run(bytes);
        }
    }
    EXPECT_GT(inputs, mutate ? 100 : 20) << target;
}

TEST(FormatsFuzzSeeds, Dsl) {
    runAll("dsl");
}
TEST(FormatsFuzzSeeds, Compressed) {
    runAll("compressed");
}
TEST(FormatsFuzzSeeds, SampleRows) {
    runAll("sample_rows");
}
TEST(FormatsFuzzSeeds, SaleaeBin) {
    runAll("saleae_bin");
}
// Cut anywhere, an FST file is refused by the block check before fstapi reads it; changed
// bytes inside a block's compressed contents can still crash fstapi itself (the `fst` fuzz
// target finds such inputs; they are fstapi's to fix).
TEST(FormatsFuzzSeeds, Fst) {
    runAll("fst", false);
}

}  // namespace
}  // namespace busdecode::test
