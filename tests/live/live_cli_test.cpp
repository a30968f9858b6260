// `decode --device` through the real CLI and libsigrok's demo driver: N samples decode
// exactly as sigrok-cli's recording of the same device; --time and Ctrl-C end a run with
// its summary; --save writes a session that decodes the same; --scan finds the demo;
// every bad device, rate or channel is one line and exit 2.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include "robustness/robustness_cli.h"
#include "support/paths.h"

namespace busdecode::test {
namespace {

const std::string kRecording = std::string(LIVE_TEST_DATA) + "/demo_1MHz_100k.sr";
// SPI on the demo's pattern: deterministic, a few hundred transfers in 0.1 s.
const std::vector<std::string> kSpi{"--proto", "spi",   "--map",   "sclk=D0",  "--map",
                                    "mosi=D1", "--map", "miso=D2", "--format", "jsonl"};

std::vector<std::string> with(std::vector<std::string> a, const std::vector<std::string>& b) {
    a.insert(a.end(), b.begin(), b.end());
    return a;
}

TEST(LiveCli, DemoSamplesDecodeAsSigrokCliRecordedThem) {
    const RunResult file = runDecode(with({kRecording}, kSpi));
    ASSERT_EQ(file.status, 0) << file.err;
    ASSERT_GT(file.out.size(), 1000u);
    const RunResult live = runDecode(with({"--device", "demo", "--samplerate", "1M", "--channels",
                                           "D0,D1,D2,D3", "--samples", "100000"},
                                          kSpi));
    EXPECT_EQ(live.status, 0) << live.err;
    EXPECT_EQ(live.out, file.out);
}

TEST(LiveCli, SavedSessionDecodesTheSame) {
    const std::string saved = tempDir() + "/saved.sr";
    const RunResult live = runDecode(with({"--device", "demo", "--samplerate", "1M", "--channels",
                                           "D0,D1,D2,D3", "--samples", "100000", "--save", saved},
                                          kSpi));
    ASSERT_EQ(live.status, 0) << live.err;
    const RunResult again = runDecode(with({saved}, kSpi));
    EXPECT_EQ(again.status, 0) << again.err;
    EXPECT_EQ(again.out, live.out);
    const RunResult recorded = runDecode(with({kRecording}, kSpi));
    EXPECT_EQ(again.out, recorded.out);
}

TEST(LiveCli, TimeEndsTheRunWithItsSummary) {
    const RunResult r =
        runDecode({"--device", "demo", "--samplerate", "100k", "--channels", "D0,D1", "--time", "3",
                   "--proto", "spi", "--map", "sclk=D0", "--map", "mosi=D1"});
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find("# summary: "), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("demo: 300000 samples at 100 kHz"), std::string::npos) << r.out;
}

TEST(LiveCli, ATimeShorterThanASampleTakesOne) {
    const RunResult r = runCommand("timeout 20 " + shellQuote(binDir() + "/decode") +
                                   " --device demo --samplerate 1M --time 0.0000001 --proto spi "
                                   "--map sclk=D0 --map mosi=D1");
    EXPECT_EQ(r.status, 0) << r.err;  // not 124: 0 samples meant no limit
    EXPECT_NE(r.out.find("demo: 1 samples at 1 MHz"), std::string::npos) << r.out;
}

// jsonl's hints (the acquisition's counts among them) go to stderr, as a file's do; the
// lines not acquired are no signals to offer.
TEST(LiveCli, JsonlHintsAndTheSignalsOffered) {
    const RunResult r = runDecode(with({"--device", "demo", "--samplerate", "1M", "--channels",
                                        "D0,D1,D2,D3", "--samples", "1000"},
                                       kSpi));
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.err.find("decode: demo: hint: demo: 1000 samples at 1 MHz"), std::string::npos)
        << r.err;
    const RunResult unbound =
        runDecode({"--device", "demo", "--samplerate", "1M", "--channels", "D2,D5,D7", "--samples",
                   "1000", "--proto", "uart", "--map", "rx=D0"});
    EXPECT_EQ(unbound.status, 2);
    EXPECT_NE(unbound.err.find("(signals: D2, D5, D7)"), std::string::npos) << unbound.err;
}

TEST(LiveCli, CtrlCEndsARunWithoutLimitWithItsSummary) {
    const std::string out = tempDir() + "/interrupted.out";
    const std::string report = tempDir() + "/interrupted_report.txt";
    // Started in the background, SIGINT once its first transfers are out.
    const std::string script =
        shellQuote(binDir() + "/decode") +
        " --device demo --samplerate 100k --channels D0,D1 --proto spi --map sclk=D0 --map "
        "mosi=D1 --report " +
        shellQuote(report) + " >" + shellQuote(out) + " & pid=$!; i=0; until grep -qs transfer " +
        shellQuote(out) +
        " || [ $i -ge 400 ]; do sleep 0.025; i=$((i+1)); done; kill -INT $pid; "
        "i=0; while kill -0 $pid 2>/dev/null && [ $i -lt 400 ]; do sleep 0.025; i=$((i+1)); "
        "done; kill -9 $pid 2>/dev/null; wait $pid";
    const RunResult r = runCommand(script);
    EXPECT_EQ(r.status, 0) << r.err;  // as a followed capture: Ctrl-C is how it ends
    EXPECT_EQ(r.err, "");
    EXPECT_NE(readFile(out).find("# summary: "), std::string::npos);
    EXPECT_NE(readFile(report).find("busdecode report"), std::string::npos);
}

TEST(LiveCli, ScanListsTheDemoDevice) {
    const RunResult r = runDecode({"--scan"});
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find("demo\tDemo device\tlogic: D0 D1 D2 D3 D4 D5 D6 D7"), std::string::npos)
        << r.out;
}

TEST(LiveCli, BadDevicesRatesAndChannelsAreOneLine) {
    EXPECT_EQ(oneLineFailure({"--device", "nosuchdriver", "--proto", "spi"}),
              "decode: --device nosuchdriver: no such libsigrok driver (decode --scan lists the "
              "attached devices)");
    EXPECT_EQ(oneLineFailure({"--device", "demo", "--samplerate", "5G", "--proto", "spi"}),
              "decode: --samplerate 5000000000: not supported by demo (it offers 1 Hz to 1 GHz "
              "in steps of 1)");
    EXPECT_EQ(oneLineFailure({"--device", "demo", "--samplerate", "fast", "--proto", "spi"})
                  .rfind("decode: --samplerate fast: expected a whole number of Hz", 0),
              0u);
    EXPECT_EQ(oneLineFailure({"--device", "demo", "--channels", "D0,X9", "--proto", "spi"}),
              "decode: --channels X9: demo has no logic channel X9 (channels: D0 D1 D2 D3 D4 D5 "
              "D6 D7)");
    EXPECT_EQ(oneLineFailure({"--device", "demo:speed=3", "--proto", "spi"}),
              "decode: --device demo:speed=3: unknown option 'speed' (conn, serialcomm)");
    EXPECT_EQ(oneLineFailure({"--samples", "10", "--proto", "spi"}),
              "decode: --samplerate, --channels, --samples, --time and --save need --device");
    EXPECT_EQ(oneLineFailure({"--device", "demo", "--samples", "0", "--proto", "spi"}),
              "decode: --samples 0: expected a whole number, 1 or more");
    for (const char* t : {"0", "1e20"})
        EXPECT_EQ(oneLineFailure({"--device", "demo", "--time", t, "--proto", "spi"}),
                  fmt::format("decode: --time {}: expected seconds, more than 0 and at most 1e7 "
                              "(leave --time out to run until Ctrl-C)",
                              t));
    EXPECT_EQ(oneLineFailure({"--device", "demo", kRecording, "--proto", "spi"}),
              "decode: --device acquires live: no capture file, --follow or verify with it");
    // A USB analyser that is not plugged in (or not permitted): nothing found.
    EXPECT_EQ(oneLineFailure({"--device", "fx2lafw", "--proto", "spi"})
                  .rfind("decode: --device fx2lafw: no device found (connected? permissions?)", 0),
              0u);
    EXPECT_EQ(oneLineFailure({"--device", "playback:file=/nonexistent.sr", "--proto", "spi"})
                  .rfind("decode: /nonexistent.sr: cannot play back: not a sigrok session", 0),
              0u);
    EXPECT_EQ(oneLineFailure({"--device", "demo", "--save", "/dev/null", "--proto", "spi"}),
              "decode: --save /dev/null: not a regular file");
    EXPECT_EQ(oneLineFailure({"--device", "demo", "--channels", "D0,D0,D1", "--proto", "spi"}),
              "decode: --channels D0,D0,D1: D0 is named twice");
    EXPECT_EQ(oneLineFailure({"--device", "", "--proto", "spi"}),
              "decode: --device: expected a value, got nothing");
    for (const char* option : {"--channels", "--samplerate"})
        EXPECT_EQ(oneLineFailure({"--device", "demo", option, "", "--proto", "spi"}),
                  fmt::format("decode: {}: expected a value, got nothing", option));
}

}  // namespace
}  // namespace busdecode::test

namespace busdecode::test {
namespace {

// The decoder held back by a slow LCM publisher (20 events/s, queue of 1, waiting), the
// acquisition's queue 2 blocks: most of the demo's packets cannot be taken.
RunResult fallingBehind(const std::string& more_args) {
    return runCommand(
        "BUSDECODE_LIVE_QUEUE=2 BUSDECODE_LCM_RATE=20 BUSDECODE_LCM_QUEUE=1 " +
        shellQuote(binDir() + "/decode") +
        " --device demo --samplerate 1M --channels D0,D1 --time 1 --proto spi --map sclk=D0 "
        "--map mosi=D1 --lcm memq://" +
        more_args);
}

TEST(LiveCli, FallingBehindDropsWholePacketsAndSaysSo) {
    const RunResult r = fallingBehind("");
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find("demo: 1000000 samples at 1 MHz"), std::string::npos) << r.out;
    const std::size_t at = r.out.find("demo: dropped ");
    ASSERT_NE(at, std::string::npos) << r.out;
    EXPECT_NE(r.out.find("decoding fell behind the device", at), std::string::npos);
    // In jsonl, each gap is an event of its own.
    const RunResult j = fallingBehind(" --format jsonl");
    EXPECT_EQ(j.status, 0) << j.err;
    EXPECT_NE(j.out.find(R"("proto":"capture","type":"samples_dropped")"), std::string::npos)
        << j.out.substr(0, 2000);
    EXPECT_NE(j.out.find(R"("errors":["samples_dropped"])"), std::string::npos);
    const RunResult bad = runCommand("BUSDECODE_LIVE_QUEUE=0 " + shellQuote(binDir() + "/decode") +
                                     " --device demo --samples 10 --proto spi --map sclk=D0 "
                                     "--map mosi=D1");
    EXPECT_EQ(bad.status, 2);
    EXPECT_EQ(bad.err, "decode: BUSDECODE_LIVE_QUEUE='0': expected a positive count\n");
}

}  // namespace
}  // namespace busdecode::test
