// Numbers from the command line, rules files and file headers are range-checked where
// they are read: out of range is one line naming the option or file and line, exit 2
// (never a SIGFPE, a negative timebase or a wrapped glitch width). Sample rates are kept
// exact (core/sample_rate.h).
#include <gtest/gtest.h>

#include "capture/capture_reader.h"
#include "core/sample_rate.h"
#include "fuzz_harness.h"
#include "robustness_cli.h"

using namespace busdecode;
using namespace busdecode::test;

namespace {

const char* kPlainCsv = "a,b\n0,1\n1,0\n0,1\n1,1\n";

TEST(Numbers, RateTooSmallIsAnErrorNotSigfpe) {
    const auto p = caseFile("slow.csv", kPlainCsv);
    const std::string err =
        oneLineFailure({p, "--proto", "uart", "--map", "rx=a", "--rate", "1e-7"});
    EXPECT_EQ(err, "decode: --rate 1e-7: is out of range (0.001 Hz to 1e+15 Hz)");
}

TEST(Numbers, RateTooLargeIsAnErrorNotANegativeTimebase) {
    const auto p = caseFile("fast.csv", kPlainCsv);
    EXPECT_EQ(oneLineFailure({p, "--proto", "uart", "--map", "rx=a", "--rate", "9.2e18"}),
              "decode: --rate 9.2e18: is out of range (0.001 Hz to 1e+15 Hz)");
}

TEST(Numbers, RateTakesAUnitAsSampleRateDoes) {
    const auto p = caseFile("units.csv", kPlainCsv);
    const auto plain = runDecode({p, "--proto", "spi", "--map", "sclk=a", "--map", "mosi=b",
                                  "--format", "jsonl", "--rate", "1000000"});
    ASSERT_EQ(plain.status, 0) << plain.err;
    for (const char* given : {"1MHz", "1 MHz", "1000 kHz", "1e6 Hz"}) {
        const auto r = runDecode({p, "--proto", "spi", "--map", "sclk=a", "--map", "mosi=b",
                                  "--format", "jsonl", "--rate", given});
        EXPECT_EQ(r.status, 0) << given << r.err;
        EXPECT_EQ(r.out, plain.out) << given;
    }
    EXPECT_EQ(
        oneLineFailure({p, "--proto", "uart", "--map", "rx=a", "--rate", "0 MHz"}),
        "decode: --rate 0 MHz: expected a positive number of Hz (like 24 MHz, 2.5 Hz or 1e6)");
}

TEST(Numbers, RulesRateOutOfRangeNamesFileAndLine) {
    const auto cap = caseFile("rules_rate.csv", kPlainCsv);
    const auto rules = caseFile("rate.toml",
                                "[decode]\nproto = \"uart\"\nmap = [\"rx=a\"]\n"
                                "rate = 1e-9\n[uart]\nmax_errors = 0\n");
    const RunResult r = runDecode({"verify", cap, "--rules", rules});
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_NE(r.err.find(rules + ":4: [decode] rate: 1e-09 Hz is out of range"), std::string::npos)
        << r.err;
}

TEST(Numbers, GlitchWidthBeyondOneSecondIsRefused) {
    const auto p = caseFile("glitch.csv", kPlainCsv);
    EXPECT_EQ(oneLineFailure({p, "--proto", "uart", "--map", "rx=a", "--rate", "1000", "--opt",
                              "glitch_ns=1e19"}),
              "decode: decoder uart: option glitch_ns=1e19: expected a number from 0 to "
              "1000000000");
}

TEST(Numbers, FractionalRatesAreExact) {
    const SampleRate r = parseSampleRate("2.5 Hz", true);
    ASSERT_TRUE(r.timebase);
    EXPECT_EQ(r.timebase->num, 2);  // 0.4 s per sample, not 1/3 s
    EXPECT_EQ(r.timebase->den, 5);
    const SampleRate k = parseSampleRate("12.5 kHz", true);
    ASSERT_TRUE(k.timebase);
    EXPECT_EQ(k.timebase->num, 1);
    EXPECT_EQ(k.timebase->den, 12'500);
    const SampleRate d = sampleRateOf(0.1);
    ASSERT_TRUE(d.timebase);
    EXPECT_EQ(d.timebase->num, 10);
    EXPECT_EQ(d.timebase->den, 1);
    EXPECT_EQ(parseSampleRate("0 Hz", true).problem, "is zero");
    EXPECT_FALSE(parseSampleRate("1 THz", true).timebase);
    EXPECT_FALSE(parseSampleRate("2e16", true).timebase);
    EXPECT_FALSE(sampleRateOf(-1).timebase);
}

TEST(Numbers, SigrokCsvSamplerateKeepsItsFraction) {
    const auto p = caseFile("frac.csv",
                            "; Channels (2/2): A, B\n; Samplerate: 2.5 Hz\n"
                            "logic,logic\n0,1\n1,1\n0,1\n");
    auto r = openCapture(p, {});
    EXPECT_EQ(r->timebase().num, 2);
    EXPECT_EQ(r->timebase().den, 5);
    // Sample 2 is at 0.8 s; rounded to 3 S/s it was 0.667 s.
    EXPECT_EQ(r->timebase().toNs(2), 800'000'000);
}

TEST(Numbers, SigrokCsvZeroSamplerateSaysZero) {
    const auto p = caseFile("zero.csv", "; Samplerate: 0 Hz\nlogic,logic\n0,1\n");
    EXPECT_EQ(oneLineFailure({p, "--proto", "uart", "--map", "rx=0"}),
              "decode: " + p + ":1: samplerate is zero");
}

TEST(Numbers, CsvTimesWithPlusExponent) {
    const auto p = caseFile("plus.csv", "Time [s],A\n0.000000e+00,1\n1.5e+0,0\n3.0E+00,1\n");
    auto r = openCapture(p, {});
    r->select({{0, -1}});
    r->initialLevels();
    EdgeBlock b;
    std::vector<Tick> times;
    while (r->next(b))
        for (const Edge& e : b.edges)
            times.push_back(e.t);
    ASSERT_EQ(times.size(), 2u);
    EXPECT_EQ(r->timebase().toNs(times[0]), 1'500'000'000);
    EXPECT_EQ(r->timebase().toNs(times[1]), 3'000'000'000);
}

}  // namespace

namespace {

// The cli_args fuzz target's seeds (fuzz/seeds/cli_args) through its harness: the out of
// range numbers refused the documented way, nothing else thrown.
TEST(Numbers, CliArgsFuzzSeedsPassTheHarness) {
    for (const char* seed : {"out_of_range", "spi_rate", "two_decoders", "tmc"}) {
        const std::string bytes = readFile(sourceDir() + "/fuzz/seeds/cli_args/" + seed);
        EXPECT_NO_THROW(busdecode::fuzz::runTarget(
            "cli_args", reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()))
            << seed;
    }
}

}  // namespace
