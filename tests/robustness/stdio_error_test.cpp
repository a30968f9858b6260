// The standard streams through the real CLI: a usage or input error with stderr closed or
// full is exit 2, never an abort; a closed, full or broken stdout is exit 2 with a
// message, never a silent 0; `-` with stdin closed is one line and exit 2, and no
// descriptor decode opens takes the place of a closed one.
#include <gtest/gtest.h>

#include "spi_vcd.h"
#include "support/paths.h"

using namespace busdecode::test;

namespace {

std::string decode() {
    return shellQuote(binDir() + "/decode");
}

TEST(StdioError, UsageErrorWithStderrClosedIsExit2) {
    const std::string missing = shellQuote(tempDir() + "/nope.vcd");
    EXPECT_EQ(runCommand(decode() + " " + missing + " --proto spi 2>&-").status, 2);
    EXPECT_EQ(runCommand(decode() + " --proto nosuch " + missing + " 2>&-").status, 2);
}

TEST(StdioError, InputErrorWithStderrFullIsExit2) {
    const std::string missing = shellQuote(tempDir() + "/nope.vcd");
    EXPECT_EQ(runCommand(decode() + " " + missing + " --proto spi 2>/dev/full").status, 2);
    EXPECT_EQ(runCommand(decode() + " verify " + missing + " --rules " + shellQuote(spiRules()) +
                         " 2>/dev/full")
                  .status,
              2);
}

TEST(StdioError, HintOnFullOrClosedStderrIsExit2) {
    // With --format jsonl the decoder's advice goes to stderr: lost, it is no success.
    const std::string capture = shellQuote(sourceDir() + "/captures/bissc_errors.vcd");
    const std::string run = decode() + " " + capture + " --proto bissc --format jsonl >/dev/null";
    ASSERT_EQ(runCommand(run).status, 0);
    EXPECT_EQ(runCommand(run + " 2>/dev/full").status, 2);
    EXPECT_EQ(runCommand(run + " 2>&-").status, 2);
}

TEST(StdioError, FullStdoutIsExit2) {
    const std::string capture = shellQuote(spiCapture("small.vcd", 20, 10'000));
    for (const std::string format : {"text", "jsonl"}) {
        const RunResult r = runCommand(decode() + " " + capture + " --proto spi --format " +
                                       format + " >/dev/full");
        EXPECT_EQ(r.status, 2) << format;
        EXPECT_EQ(r.err, "decode: standard output: cannot write: No space left on device\n");
    }
    const RunResult v = runCommand(decode() + " verify " + capture + " --rules " +
                                   shellQuote(spiRules()) + " >/dev/full");
    EXPECT_EQ(v.status, 2);
    EXPECT_EQ(v.err, "decode verify: standard output: cannot write: No space left on device\n");
    for (const std::string option : {"--list", "--help", "--version"}) {
        const RunResult l = runCommand(decode() + " " + option + " >/dev/full");
        EXPECT_EQ(l.status, 2) << option;
        EXPECT_EQ(l.err, "decode: standard output: cannot write: No space left on device\n");
    }
}

TEST(StdioError, ClosedStdoutIsExit2) {
    const std::string capture = shellQuote(spiCapture("small.vcd", 20, 10'000));
    const RunResult r = runCommand(decode() + " " + capture + " --proto spi >&-");
    EXPECT_EQ(r.status, 2);
    EXPECT_EQ(r.err.rfind("decode: standard output: cannot write: ", 0), 0u) << r.err;
}

TEST(StdioError, BrokenPipeWithSigpipeIgnoredIsExit2) {
    // More output than the pipe holds, into a reader that leaves early.
    const std::string capture = shellQuote(spiCapture("long.vcd", 3000, 4000));
    const std::string status = shellQuote(tempDir() + "/pipe.status");
    const RunResult r =
        runCommand("trap '' PIPE; { " + decode() + " " + capture + " --proto spi; echo $? >" +
                   status + "; } | head -c 100 >/dev/null; cat " + status);
    EXPECT_EQ(r.out, "2\n");
    EXPECT_EQ(r.err, "decode: standard output: cannot write: Broken pipe\n");
}

TEST(StdioError, DashWithStdinClosedIsAnError) {
    const RunResult r = runCommand("timeout -s KILL 20 " + decode() + " - --proto spi <&-");
    EXPECT_EQ(r.status, 2);
    EXPECT_EQ(r.err, "decode: -: standard input is closed\n");
}

TEST(StdioError, ClosedStdinUnusedIsNoMatter) {
    const std::string capture = shellQuote(spiCapture("small.vcd", 20, 10'000));
    const RunResult r = runCommand(decode() + " " + capture + " --proto spi <&-");
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find("# spi: 20 transfer"), std::string::npos) << r.out;
}

}  // namespace
