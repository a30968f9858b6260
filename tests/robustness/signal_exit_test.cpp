// SIGINT and SIGTERM through the real CLI: a run waiting on a FIFO without a writer (with
// or without --follow, also in verify) and an ordinary decode cut short both end at once
// with 128 + the signal, one line saying where, and an earlier report left as it was; a
// followed capture, compressed or not, still ends cleanly. A capture truncated while read is an
// input error.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>

#include "capture/capture_reader.h"
#include "core/options.h"
#include "spi_vcd.h"
#include "support/paths.h"

using namespace busdecode::test;
namespace fs = std::filesystem;

namespace {

const char* const kEarlierReport = "an earlier report\n";

// Polls a shell condition every 25 ms for up to 20 s.
std::string waitUntil(const std::string& condition) {
    return "i=0; until " + condition + " || [ $i -ge 800 ]; do sleep 0.025; i=$((i+1)); done; ";
}

// Starts `decode ARGS` (ARGS shell-quoted by the caller, redirections included) in the
// background, runs `then`, waits until `ready` holds, sends `signal` and returns decode's
// status and stderr. Decode still running 20 s later is killed (status 137).
RunResult signalWhen(const std::string& args, const std::string& then, const std::string& ready,
                     const std::string& signal) {
    static int n = 0;
    const std::string err = shellQuote(tempDir() + "/signal" + std::to_string(++n) + ".err");
    const std::string script =
        shellQuote(binDir() + "/decode") + " " + args + " 2>" + err + " & pid=$!; " + then + "; " +
        waitUntil(ready) + "kill -" + signal + " $pid; " + waitUntil("! kill -0 $pid 2>/dev/null") +
        "kill -9 $pid 2>/dev/null; wait $pid; s=$?; cat " + err + " >&2; exit $s";
    return runCommand(script);
}

std::string fifo(const std::string& name) {
    const std::string path = tempDir() + "/" + name;
    EXPECT_EQ(mkfifo(path.c_str(), 0600), 0);
    return path;
}

// decode has `path` open (a FIFO open no longer blocks until a writer comes).
std::string hasOpen(const std::string& path) {
    return "ls -l /proc/$pid/fd 2>/dev/null | grep -qF " + shellQuote(path);
}

TEST(SignalExit, FifoWithoutWriterEndsOnSigint) {
    const std::string f = fifo("nowriter.vcd");
    const RunResult r =
        signalWhen(shellQuote(f) + " --proto spi >/dev/null", ":", hasOpen(f), "INT");
    EXPECT_EQ(r.status, 130) << r.err;
    EXPECT_EQ(r.err, "decode: " + f + ": interrupted, after reading 0 bytes (SIGINT)\n");
}

// A sigrok session (a ZIP, read by offset) written into a FIFO is copied and decoded as
// the file itself is.
TEST(SignalExit, ASessionThroughAFifoDecodesAsTheFile) {
    const std::string f = fifo("session.sr");
    const std::string sr = sourceDir() + "/tests/data/real/sigrok-dumps/spi/spi-count-msb.sr";
    const std::string args =
        " --proto spi --map cs=1 --map sclk=0 --map mosi=2 --opt bits=8 --format jsonl";
    const RunResult direct =
        runCommand(shellQuote(binDir() + "/decode") + " " + shellQuote(sr) + args);
    ASSERT_EQ(direct.status, 0) << direct.err;
    const RunResult piped =
        runCommand("cat " + shellQuote(sr) + " > " + shellQuote(f) + " & " +
                   shellQuote(binDir() + "/decode") + " " + shellQuote(f) + args);
    EXPECT_EQ(piped.status, 0) << piped.err;
    EXPECT_FALSE(direct.out.empty());
    EXPECT_EQ(piped.out, direct.out);
}

TEST(SignalExit, FollowedFifoWithoutWriterEndsOnSigterm) {
    const std::string f = fifo("follow_nowriter.vcd");
    const RunResult r =
        signalWhen(shellQuote(f) + " --proto spi --follow >/dev/null", ":", hasOpen(f), "TERM");
    EXPECT_EQ(r.status, 143) << r.err;
    EXPECT_EQ(r.err, "decode: " + f +
                         ": stopped (SIGTERM) while following, before its header was complete: "
                         "nothing decoded\n");
}

TEST(SignalExit, VerifyOnFifoWithoutWriterEndsOnSigint) {
    const std::string f = fifo("verify_nowriter.vcd");
    const std::string rules = spiRules();
    const std::string junit = tempDir() + "/verify_nowriter.xml";
    writeFile(junit, kEarlierReport);
    const RunResult r = signalWhen("verify " + shellQuote(f) + " --rules " + shellQuote(rules) +
                                       " --junit " + shellQuote(junit) + " >/dev/null",
                                   ":", hasOpen(f), "INT");
    EXPECT_EQ(r.status, 130) << r.err;
    EXPECT_EQ(r.err,
              "decode verify: interrupted (SIGINT) after 0 of 1 captures; nothing written to the "
              "JUnit file\n");
    EXPECT_EQ(readFile(junit), kEarlierReport);
}

// No file in `dir` but `keep` (no temporary report left behind).
void expectOnly(const std::string& dir, const std::string& keep) {
    for (const auto& e : fs::directory_iterator(dir))
        EXPECT_EQ(e.path().filename().string(), keep) << "left behind: " << e.path();
}

TEST(SignalExit, InterruptedReadLeavesTheEarlierReport) {
    // Half a capture written into a FIFO, which then stays open: decode has read it and
    // waits for the rest when SIGINT comes.
    const std::string text = spiVcd(2000, 4000);
    const std::string part = tempDir() + "/half.vcd";
    writeFile(part, text.substr(0, text.size() / 2));
    const std::string f = fifo("fed.vcd");
    const std::string dir = tempDir() + "/fed_reports";
    fs::create_directories(dir);
    const std::string report = dir + "/report.txt";
    writeFile(report, kEarlierReport);
    const RunResult r =
        signalWhen(shellQuote(f) + " --proto spi --report " + shellQuote(report) + " >/dev/null",
                   "exec 3>" + shellQuote(f) + "; cat " + shellQuote(part) + " >&3", ":", "INT");
    EXPECT_EQ(r.status, 130) << r.err;
    EXPECT_EQ(r.err.rfind("decode: " + f + ": interrupted", 0), 0u) << r.err;
    EXPECT_NE(r.err.find(", after reading "), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(" bytes (SIGINT); nothing written to the report\n"), std::string::npos)
        << r.err;
    EXPECT_EQ(readFile(report), kEarlierReport);
    expectOnly(dir, "report.txt");
}

TEST(SignalExit, InterruptedDecodeSaysWhereAndLeavesTheEarlierReport) {
    // Ten seconds of capture at its own pace (paced by blocks of edges: many words make
    // many blocks): SIGTERM comes after its first words.
    const std::string capture = spiCapture("sparse.vcd", 2000, 5'000'000);
    const std::string dir = tempDir() + "/paced_reports";
    fs::create_directories(dir);
    const std::string report = dir + "/report.txt";
    writeFile(report, kEarlierReport);
    const std::string out = tempDir() + "/paced.out";
    const RunResult r = signalWhen(shellQuote(capture) + " --proto spi --realtime --report " +
                                       shellQuote(report) + " >" + shellQuote(out),
                                   ":", "grep -qs transfer " + shellQuote(out), "TERM");
    EXPECT_EQ(r.status, 143) << r.err;
    EXPECT_EQ(r.err.rfind("decode: " + capture + ": interrupted ", 0), 0u) << r.err;
    EXPECT_NE(r.err.find(" s into the capture, after reading "), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(" bytes (SIGTERM); nothing written to the report\n"), std::string::npos)
        << r.err;
    EXPECT_EQ(readFile(report), kEarlierReport);
    expectOnly(dir, "report.txt");
    // Stopped promptly: far from all words were decoded.
    const std::string text = readFile(out);
    EXPECT_LT(std::count(text.begin(), text.end(), '\n'), 1000);
}

TEST(SignalExit, FollowedCaptureStillEndsCleanly) {
    const std::string capture = spiCapture("followed.vcd", 4, 10'000);
    const std::string report = tempDir() + "/followed_report.txt";
    const std::string out = tempDir() + "/followed.out";
    const RunResult r = signalWhen(shellQuote(capture) + " --proto spi --follow --report " +
                                       shellQuote(report) + " >" + shellQuote(out),
                                   ":", "grep -qs transfer " + shellQuote(out), "INT");
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.err, "");
    EXPECT_NE(readFile(report).find("busdecode report"), std::string::npos);
}

// The decompressing thread ends the text where the followed file was stopped: read to
// there, not cut as an interrupted read ("before its header was complete").
TEST(SignalExit, FollowedCompressedCaptureStillEndsCleanly) {
    const std::string capture = spiCapture("followed_gz.vcd", 4, 10'000);
    ASSERT_EQ(runCommand("gzip -f " + shellQuote(capture)).status, 0);
    const std::string report = tempDir() + "/followed_gz_report.txt";
    const std::string out = tempDir() + "/followed_gz.out";
    const RunResult r = signalWhen(shellQuote(capture + ".gz") + " --proto spi --follow --report " +
                                       shellQuote(report) + " >" + shellQuote(out),
                                   ":", "grep -qs transfer " + shellQuote(out), "INT");
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.err, "");
    EXPECT_NE(readFile(report).find("busdecode report"), std::string::npos);
}

// Reads a capture through openCapture, truncates it to `keep` bytes after the first
// block, and reads on: the reader must say so, not end as if the capture ended there.
void expectTruncationReported(const std::string& name, const std::string& text,
                              const busdecode::OpenOptions& opts) {
    using namespace busdecode;
    const std::string path = tempDir() + "/" + name;
    writeFile(path, text);
    auto reader = openCapture(path, opts);
    std::vector<LineRef> lines;
    for (std::size_t i = 0; i < reader->signals().size(); ++i)
        lines.push_back({int(i), -1});
    reader->select(lines);
    reader->initialLevels();
    EdgeBlock block;
    ASSERT_TRUE(reader->next(block));
    ASSERT_EQ(truncate(path.c_str(), 1000), 0);
    try {
        while (reader->next(block)) {
        }
        ADD_FAILURE() << name << ": no error";
    } catch (const InputError& e) {
        const std::string what = e.what();
        EXPECT_EQ(what.rfind(path + ": truncated while read (ended at byte ", 0), 0u) << what;
    }
}

TEST(SignalExit, CaptureTruncatedWhileReadIsAnInputError) {
    busdecode::OpenOptions one_thread;
    one_thread.read_ahead = false;
    expectTruncationReported("truncated.vcd", spiVcd(2000, 4000), one_thread);
    // A CSV read ahead on a thread of its own (FileReadAhead).
    std::string csv = "Time [s],cs,sclk\n";
    for (int i = 0; i < 600000; ++i)
        csv += std::to_string(i * 1e-6) + "," + std::to_string(i & 1) + "," +
               std::to_string((i >> 1) & 1) + "\n";
    expectTruncationReported("truncated.csv", csv, {});
}

}  // namespace
