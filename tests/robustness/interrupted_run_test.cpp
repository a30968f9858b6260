// The CLI when its run is cut short: a followed capture deleted or truncated under it
// must end with one clear error (exit 2), and a decode killed with SIGKILL while it
// works towards a --report must leave no report file behind (reports are written to a
// temporary file and renamed), only ever a complete one.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>

#include "capture/capture_writer.h"
#include "support/paths.h"
#ifdef FUZZ_HAVE_SPI
#include "spi_generator.h"
#endif

using namespace busdecode::test;
namespace fs = std::filesystem;

namespace {

// A valid VCD with eight SPI words (mode 3) and the four lines idle after them.
std::string spiVcd() {
    std::string v =
        "$timescale 1 ns $end\n$scope module top $end\n"
        "$var wire 1 ! cs $end\n$var wire 1 \" sclk $end\n$var wire 1 # mosi $end\n"
        "$var wire 1 $ miso $end\n$upscope $end\n$enddefinitions $end\n"
        "#0 1! 1\" 0# 0$\n";
    long t = 1000;
    for (int w = 0; w < 8; ++w) {
        v += "#" + std::to_string(t) + " 0!\n";
        t += 100;
        for (int b = 0; b < 32; ++b) {
            v += "#" + std::to_string(t) + " 0\" " + ((b + w) % 3 ? "1#" : "0#") + "\n";
            v += "#" + std::to_string(t + 50) + " 1\"\n";
            t += 100;
        }
        v += "#" + std::to_string(t + 100) + " 1!\n";
        t += 1000;
    }
    v += "#" + std::to_string(t + 100000) + "\n";
    return v;
}

// Runs `decode FILE --proto spi --follow`, waits until it has printed an event, applies
// `action` to the file (a shell command on "$F"), and returns decode's status and stderr.
RunResult followThen(const std::string& name, const std::string& action) {
    const std::string dir = tempDir();
    const std::string file = dir + "/" + name;
    writeFile(file, spiVcd());
    const std::string script =
        "F=" + shellQuote(file) + "; O=" + shellQuote(file + ".out") +
        "; E=" + shellQuote(file + ".err") + "; " + shellQuote(binDir() + "/decode") +
        " \"$F\" --proto spi --follow >\"$O\" 2>\"$E\" & pid=$!; "
        "i=0; while [ ! -s \"$O\" ] && [ $i -lt 400 ]; do sleep 0.025; i=$((i+1)); done; " +
        action +
        "; i=0; while kill -0 $pid 2>/dev/null && [ $i -lt 400 ]; do sleep 0.025; i=$((i+1)); "
        "done; "
        "kill -9 $pid 2>/dev/null; wait $pid; s=$?; cat \"$E\" >&2; exit $s";
    return runCommand(script);
}

TEST(InterruptedRun, FollowedFileDeleted) {
    const RunResult r = followThen("deleted.vcd", "rm -f \"$F\"");
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_EQ(r.err, "decode: " + tempDir() + "/deleted.vcd: deleted while following\n");
}

TEST(InterruptedRun, FollowedFileTruncated) {
    const RunResult r = followThen("truncated.vcd", ": > \"$F\"");
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_EQ(r.err, "decode: " + tempDir() + "/truncated.vcd: truncated while following\n");
}

#ifdef FUZZ_HAVE_SPI
// About 25 MB of back-to-back SPI at 100 MHz sampling: long enough to kill mid-run.
std::string bigCapture() {
    using namespace busdecode;
    const std::string path = tempDir() + "/big_spi.vcd";
    if (fs::exists(path)) return path;
    SpiTiming timing{100, 50, 50, 20};
    WaveBuilder wb(Timebase::fromSampleRate(100'000'000), {"cs", "sclk", "mosi", "miso"},
                   SpiGenerator::idleLevels({}));
    SpiGenerator gen(wb, SpiLines{0, 1, 2, 3}, {}, timing);
    double t = 100;
    std::uint32_t x = 12345;
    for (int i = 0; i < 2000; ++i) {
        std::vector<SpiGenerator::Word> words(8);
        for (auto& w : words) {
            x = x * 1664525u + 1013904223u;
            w = {x, ~x};
        }
        t = gen.transfer(t, words, 32) + 100;
    }
    writeVcd(wb.build(wb.ticksFromNs(t)), path);
    return path;
}

TEST(InterruptedRun, FollowStoppedBeforeItsHeaderWasCompleteSaysSo) {
    const std::string file = tempDir() + "/half-header.vcd";
    const std::string vcd = spiVcd();
    writeFile(file, vcd.substr(0, vcd.find("$enddefinitions")));
    const RunResult r = runCommand(shellQuote(binDir() + "/decode") + " " + shellQuote(file) +
                                   " --proto spi --follow & pid=$!; sleep 0.5; kill -INT $pid; "
                                   "wait $pid");
    EXPECT_EQ(r.status, 130) << r.err;  // nothing was decoded: cut short, as without --follow
    EXPECT_EQ(r.err, "decode: " + file +
                         ": stopped (SIGINT) while following, before its header was complete: "
                         "nothing decoded\n");
}

TEST(InterruptedRun, KilledDecodeLeavesNoPartialReport) {
    const std::string capture = bigCapture();
    const std::string dir = tempDir() + "/reports";
    fs::create_directories(dir);
    // An uninterrupted run: how long it takes, and what a complete report looks like.
    const std::string full = dir + "/full.txt";
    const auto t0 = std::chrono::steady_clock::now();
    const RunResult done = runDecode({capture, "--proto", "spi", "--report", full});
    const double secs =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    ASSERT_EQ(done.status, 0) << done.err;
    ASSERT_TRUE(fs::exists(full));
    const std::string reference = readFile(full);
    ASSERT_FALSE(reference.empty());

    for (double fraction : {0.1, 0.4, 0.7}) {
        const std::string report = dir + "/killed" + std::to_string(int(fraction * 10)) + ".txt";
        const std::string script =
            shellQuote(binDir() + "/decode") + " " + shellQuote(capture) +
            " --proto spi --report " + shellQuote(report) + " >/dev/null 2>&1 & pid=$!; sleep " +
            std::to_string(fraction * secs) + "; kill -9 $pid 2>/dev/null; wait $pid; exit $?";
        const RunResult r = runCommand(script);
        // Killed before the rename: no report. Killed after it (e.g. while a sanitizer's
        // exit-time checks run) or not killed at all: the report is whole, ending the
        // way the uninterrupted one does. Never half a report.
        if (fs::exists(report)) {
            const std::string text = readFile(report);
            const auto tail = reference.substr(reference.rfind('\n', reference.size() - 2) + 1);
            EXPECT_TRUE(text.size() >= tail.size() &&
                        text.compare(text.size() - tail.size(), tail.size(), tail) == 0)
                << "a partial report " << report << " (status " << r.status << ")";
        } else {
            EXPECT_NE(r.status, 0) << "decode finished but wrote no report " << report;
        }
    }
}
#endif

}  // namespace
