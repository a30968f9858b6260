// ScratchDir: a unique directory, removed with its files by the process that made it,
// kept when asked, and never removed by a forked child that exits normally.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include <sys/wait.h>
#include <unistd.h>

#include "core/scratch_dir.h"

namespace busdecode {
namespace {

namespace fs = std::filesystem;

TEST(ScratchDir, UniqueAndRemovedWithItsFiles) {
    std::string first, second;
    {
        ScratchDir a("busdecode-scratch-test"), b("busdecode-scratch-test");
        first = a.path();
        second = b.path();
        EXPECT_NE(first, second);
        EXPECT_EQ(fs::path(first).filename().string().rfind("busdecode-scratch-test-", 0), 0u);
        ASSERT_TRUE(fs::is_directory(first));
        fs::create_directory(fs::path(first) / "sub");
        std::ofstream(fs::path(first) / "sub" / "f.txt") << "x";
    }
    EXPECT_FALSE(fs::exists(first));
    EXPECT_FALSE(fs::exists(second));
}

TEST(ScratchDir, KeptWhenAsked) {
    std::string path;
    {
        ScratchDir kept("busdecode-scratch-test", true);
        path = kept.path();
    }
    EXPECT_TRUE(fs::is_directory(path));
    fs::remove_all(path);
}

TEST(ScratchDir, AForkedChildLeavesItToItsParent) {
    ScratchDir dir("busdecode-scratch-test");
    const pid_t child = fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
        // What a normal exit would do to the child's copy of the object; then leave
        // without running anything else of the test process.
        dir.~ScratchDir();
        _exit(0);
    }
    int status = 0;
    ASSERT_EQ(waitpid(child, &status, 0), child);
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
    EXPECT_TRUE(fs::is_directory(dir.path()));
}

}  // namespace
}  // namespace busdecode
