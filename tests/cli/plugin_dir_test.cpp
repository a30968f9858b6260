// `decode` copied without its plugins: one line naming where it looked and how to point it
// at them, exit 2; with BUSDECODE_PLUGIN_PATH set it finds them again.
#include <gtest/gtest.h>

#include <filesystem>

#include "support/paths.h"

using namespace busdecode::test;

namespace {

// A copy of build/bin/decode alone in a fresh directory (its RPATH still finds the core).
std::string lonelyDecode() {
    const std::string dir = tempDir() + "/lonely/bin";
    std::filesystem::create_directories(dir);
    const std::string copy = dir + "/decode";
    std::filesystem::copy_file(binDir() + "/decode", copy,
                               std::filesystem::copy_options::overwrite_existing);
    return copy;
}

RunResult runWithoutPluginPath(const std::string& decode, const std::string& args) {
    return runCommand("env -u BUSDECODE_PLUGIN_PATH " + shellQuote(decode) + " " + args);
}

}  // namespace

TEST(PluginDir, MissingPluginsNameTheDirectoriesSearchedAndTheVariable) {
    const std::string decode = lonelyDecode();
    const std::string capture = sourceDir() + "/captures/bissc_1mhz_26bit.vcd";
    for (const std::string& args :
         {shellQuote(capture) + " --proto bissc", std::string("--list")}) {
        const RunResult r = runWithoutPluginPath(decode, args);
        EXPECT_EQ(r.status, 2) << args << "\n" << r.err;
        EXPECT_EQ(r.out, "") << args;
        const std::string bin = std::filesystem::path(decode).parent_path().string();
        EXPECT_NE(r.err.find("no decoder plugins (busdecode_*.so) found; searched: " + bin +
                             "/plugins, "),
                  std::string::npos)
            << r.err;
        EXPECT_NE(r.err.find("/lonely/lib/busdecode/plugins"), std::string::npos) << r.err;
        EXPECT_NE(r.err.find("set BUSDECODE_PLUGIN_PATH"), std::string::npos) << r.err;
        EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << "one line: " << r.err;
    }
}

TEST(PluginDir, ThePluginPathVariableFindsThem) {
    const std::string decode = lonelyDecode();
    const RunResult r = runCommand("BUSDECODE_PLUGIN_PATH=" + shellQuote(binDir() + "/plugins") +
                                   " " + shellQuote(decode) + " " +
                                   shellQuote(sourceDir() + "/captures/bissc_1mhz_26bit.vcd") +
                                   " --proto bissc --format jsonl");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find("\"proto\":\"bissc\""), std::string::npos) << r.out.substr(0, 300);
}
