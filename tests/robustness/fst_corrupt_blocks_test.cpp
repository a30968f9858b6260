// FST files with corrupt blocks (regressions/fst/: des.fst with bytes changed, a chain
// table that made fstapi free an invalid pointer, a block asking for a terabyte, a time
// table of 2^27 items; the fuzzer's unfinished block whose length wrapped fstapi's walk
// round for ever): decode exits 2 with one line naming the file and the block.
#include <gtest/gtest.h>

#include <atomic>
#include <filesystem>

#include "capture/fst_api_process.h"
#include "robustness_cli.h"

namespace busdecode::test {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> corruptFstFiles() {
    std::vector<std::string> out;
    for (const auto& f : fs::directory_iterator(fs::path(ROBUSTNESS_REGRESSIONS_DIR) / "fst"))
        if (f.path().filename().string().front() != '.') out.push_back(f.path().string());
    std::sort(out.begin(), out.end());
    return out;
}

TEST(FstCorruptBlocks, EachExitsTwoWithOneLineNamingFileAndBlock) {
    const auto files = corruptFstFiles();
    ASSERT_GE(files.size(), 3u);
    for (const std::string& f : files) {
        SCOPED_TRACE(f);
        const std::string err = oneLineFailure({"--proto", "ssi", "--map", "clk=top.clk", f});
        EXPECT_EQ(err.rfind("decode: " + f + ": FST block ", 0), 0u) << err;
    }
}

TEST(FstCorruptBlocks, TheInvalidFreeIsInTheBlockItCorrupts) {
    const std::string f =
        (fs::path(ROBUSTNESS_REGRESSIONS_DIR) / "fst" / "invalid_free_chain_table").string();
    const std::string err = oneLineFailure({"--proto", "ssi", "--map", "clk=top.clk", f});
    EXPECT_EQ(err.rfind("decode: " + f + ": FST block 1 at byte 330: ", 0), 0u) << err;
}

TEST(FstCorruptBlocks, TheHeapCorruptionEndsOnlyFstapisProcess) {
    const std::string f =
        (fs::path(ROBUSTNESS_REGRESSIONS_DIR) / "fst" / "invalid_free_chain_table").string();
    const std::string err = oneLineFailure({"--proto", "ssi", "--map", "clk=top.clk", f});
    EXPECT_NE(err.find("fstapi failed unpacking it ("), std::string::npos) << err;
}

TEST(FstCorruptBlocks, ABlockAskingForMoreThanTheBudgetIsRefusedBeforeFstapi) {
    const std::string f =
        (fs::path(ROBUSTNESS_REGRESSIONS_DIR) / "fst" / "block_needs_a_terabyte").string();
    const std::string err = oneLineFailure({"--formats", f});
    EXPECT_NE(err.find("needs 1048577 MB to unpack, more than the 256 MB"), std::string::npos)
        << err;
}

// A loop inside fstapi (none is known since the block walk checks lengths first) ends the
// child at its processor-time limit, which the reader reports as the way it ended.
TEST(FstCorruptBlocks, AChildThatLoopsIsEndedByItsCpuLimit) {
    FstChild child("loop.fst", std::uint64_t(64) << 20, 1, [](ChildChannel&) {
        std::atomic<std::uint64_t> spins{0};
        for (;;)
            spins.fetch_add(1, std::memory_order_relaxed);
    });
    std::uint8_t kind = 0;
    std::string payload;
    EXPECT_FALSE(child.channel().receive(kind, payload));
    EXPECT_NE(child.howItEnded().find("CPU time limit exceeded"), std::string::npos);
}

}  // namespace
}  // namespace busdecode::test
