// Differential tests against the real sigrok-cli (Debian package sigrok-cli): the same
// capture decoded by sigrok's SPI decoder and by ours must give the same words over the
// same sample ranges. Covers every capture of sigrok-dumps spi/allmodes (all CPOL/CPHA,
// cs polarity, LSB first, triggers mid-transfer) and a generated capture written as VCD
// and as a sigrok session.
// Skipped when sigrok-cli is not installed.
#include <gtest/gtest.h>

#include <filesystem>
#include <random>
#include <regex>
#include <sstream>

#include "capture/capture_reader.h"
#include "capture/capture_writer.h"
#include "core/registry.h"
#include "core/session.h"
#include "spi_generator.h"
#include "spi_info.h"
#include "support/decode_events.h"
#include "support/paths.h"

using namespace busdecode;
using namespace busdecode::test;

namespace {

bool haveSigrokCli() {
    return runCommand("command -v sigrok-cli >/dev/null 2>&1").status == 0;
}

struct Word {
    Tick ss, es;
    std::uint64_t mosi, miso;
    bool operator==(const Word&) const = default;
};

std::string show(const std::vector<Word>& ws) {
    std::ostringstream s;
    for (const auto& w : ws)
        s << w.ss << "-" << w.es << " " << std::hex << w.mosi << "/" << w.miso << std::dec << "\n";
    return s.str();
}

struct BusSetup {
    std::string cs, sclk, mosi, miso;  // channel names
    int cpol = 0, cpha = 0, bits = 8;
    bool lsb = false, cs_high = false;
    std::string input_format;  // sigrok-cli -I (empty: by extension)
};

// sigrok: one decoder instance per data line, so mosi-data and miso-data can be told
// apart in sigrok-cli 0.7's output ("ss-es spi-1: HEX").
std::vector<Word> sigrokWords(const std::string& file, const BusSetup& s) {
    std::string common = ":clk=" + s.sclk + ":cs=" + s.cs + ":cpol=" + std::to_string(s.cpol) +
                         ":cpha=" + std::to_string(s.cpha) + ":wordsize=" + std::to_string(s.bits) +
                         ":bitorder=" + (s.lsb ? "lsb-first" : "msb-first") +
                         ":cs_polarity=" + (s.cs_high ? "active-high" : "active-low");
    std::string cmd = "sigrok-cli " + (s.input_format.empty() ? "" : "-I " + s.input_format + " ") +
                      "-i " + shellQuote(file) + " -P " +
                      shellQuote("spi:mosi=" + s.mosi + common) + " -P " +
                      shellQuote("spi:miso=" + s.miso + common) +
                      " -A spi=mosi-data:miso-data --protocol-decoder-samplenum";
    RunResult r = runCommand(cmd);
    EXPECT_EQ(r.status, 0) << cmd << "\n" << r.err;
    std::map<std::pair<Tick, Tick>, Word> by_range;
    std::regex re(R"(^(\d+)-(\d+) spi-([12]): ([0-9A-F]+)$)");
    std::istringstream in(r.out);
    std::string line;
    while (std::getline(in, line)) {
        std::smatch m;
        if (!std::regex_match(line, m, re)) continue;
        Tick ss = std::stoll(m[1]), es = std::stoll(m[2]);
        auto& w = by_range.try_emplace({ss, es}, Word{ss, es, 0, 0}).first->second;
        (m[3] == "1" ? w.mosi : w.miso) = std::stoull(m[4], nullptr, 16);
    }
    std::vector<Word> out;
    for (const auto& [k, w] : by_range)
        out.push_back(w);
    return out;
}

std::vector<Word> ourWords(const std::string& file, const BusSetup& s) {
    Registry::instance().add(makeSpiFactory());
    std::map<std::string, std::string> opts = {
        {"cpol", std::to_string(s.cpol)},
        {"cpha", std::to_string(s.cpha)},
        {"bits", std::to_string(s.bits)},
        {"lsb_first", s.lsb ? "1" : "0"},
        {"cs_polarity", s.cs_high ? "active-high" : "active-low"}};
    const auto events = decodeEvents(
        file,
        {DecoderRequest{
            "spi", {{"cs", s.cs}, {"sclk", s.sclk}, {"mosi", s.mosi}, {"miso", s.miso}}, opts}});
    std::vector<Word> out;
    for (const auto& e : events) {
        if (e.hasError("short_frame")) continue;  // sigrok drops words cut short silently
        out.push_back({e.start, e.end, std::get<std::uint64_t>(*e.get("mosi")),
                       std::get<std::uint64_t>(*e.get("miso"))});
    }
    std::sort(out.begin(), out.end(), [](const Word& a, const Word& b) { return a.ss < b.ss; });
    return out;
}

}  // namespace

TEST(SpiVsSigrokCli, AllModesCaptures) {
    if (!haveSigrokCli()) GTEST_SKIP() << "sigrok-cli not installed";
    const std::string dir = realCaptures() + "/sigrok-dumps/spi/allmodes";
    std::regex name(R"(spi_0x([0-9a-f]+)_cpol(\d)_cpha(\d)_.*\.sr)");
    int files = 0, words = 0;
    for (const auto& entry : std::filesystem::directory_iterator(dir)) {
        const std::string fname = entry.path().filename().string();
        std::smatch m;
        if (!std::regex_match(fname, m, name)) continue;
        SCOPED_TRACE(fname);
        BusSetup s;
        s.cs = "CS#";
        s.sclk = "CLK";
        s.mosi = "MOSI";
        s.miso = "MISO";
        s.bits = int(m[1].length()) * 4;
        s.cpol = std::stoi(m[2]);
        s.cpha = std::stoi(m[3]);
        s.lsb = fname.find("lsbfirst") != std::string::npos;
        s.cs_high = fname.find("csactivehigh") != std::string::npos;
        auto want = sigrokWords(entry.path().string(), s);
        auto got = ourWords(entry.path().string(), s);
        EXPECT_EQ(show(got), show(want));
        ++files;
        words += int(want.size());
    }
    EXPECT_GE(files, 50);
    EXPECT_GE(words, 50);
}

// Written as VCD and as a sigrok session (writeSr: sigrok-cli must read ours as its own).
TEST(SpiVsSigrokCli, GeneratedVcdAndSrInEveryMode) {
    if (!haveSigrokCli()) GTEST_SKIP() << "sigrok-cli not installed";
    std::mt19937_64 rng(42);
    for (int run = 0; run < 8; ++run) {
        const int mode = run % 4;
        const std::string ext = run < 4 ? "vcd" : "sr";
        SCOPED_TRACE(::testing::Message() << "mode " << mode << " " << ext);
        SpiMode m{mode >> 1, mode & 1, mode == 2, false};
        const int bits = 8 + 8 * mode;  // 8, 16, 24, 32
        std::vector<std::vector<SpiGenerator::Word>> transfers;
        for (int i = 0; i < 12; ++i) {
            const std::uint64_t mask = (1ull << bits) - 1;
            transfers.push_back({{rng() & mask, rng() & mask}, {rng() & mask, rng() & mask}});
        }
        Waveform w = makeSpiCapture(transfers, bits, m, SpiTiming{200, 100, 100, 20}, 500);
        const std::string file = tempDir() + "/spi_mode" + std::to_string(mode) + "." + ext;
        if (ext == "vcd")
            writeVcd(w, file);
        else
            writeSr(w, file);
        BusSetup s{"cs",   "sclk", "mosi",      "miso", m.cpol,
                   m.cpha, bits,   m.lsb_first, false,  ext == "vcd" ? "vcd" : ""};
        auto want = sigrokWords(file, s);
        auto got = ourWords(file, s);
        ASSERT_EQ(want.size(), 24u);
        EXPECT_EQ(show(got), show(want));
    }
}

TEST(SpiVsSigrokCli, SrAndItsVcdAndCsvExportsDecodeIdentically) {
    // The same real traffic read from the .sr, from sigrok-cli's VCD (10 ns timescale,
    // several changes per timestamp line) and from its dense CSV: identical words at
    // identical times.
    if (!haveSigrokCli()) GTEST_SKIP() << "sigrok-cli not installed";
    Registry::instance().add(makeSpiFactory());
    const std::string sr = realCaptures() + "/sigrok-dumps/spi/adf4351/set-4000mhz.sr";
    const std::string vcd = tempDir() + "/adf4351.vcd", csv = tempDir() + "/adf4351.csv";
    ASSERT_EQ(
        runCommand("sigrok-cli -i " + shellQuote(sr) + " -O vcd -o " + shellQuote(vcd)).status, 0);
    ASSERT_EQ(
        runCommand("sigrok-cli -i " + shellQuote(sr) + " -O csv -o " + shellQuote(csv)).status, 0);
    auto decodeNs = [](const std::string& file) {
        CaptureFacts facts;
        const auto events =
            decodeEvents(file,
                         {DecoderRequest{"spi",
                                         {{"cs", "CS#"}, {"sclk", "CLK"}, {"mosi", "MOSI"}},
                                         {{"cpol", "0"}, {"cpha", "0"}}}},
                         {}, &facts);
        const Timebase tb = facts.timebase;
        std::vector<std::string> out;
        for (const auto& e : events)
            out.push_back(std::to_string(tb.toNs(e.start)) + "-" + std::to_string(tb.toNs(e.end)) +
                          " " + e.summary);
        return out;
    };
    auto from_sr = decodeNs(sr);
    ASSERT_EQ(from_sr.size(), 6u);
    EXPECT_EQ(from_sr[0], "99555750-100003000 MOSI 0x00D80005");
    EXPECT_EQ(decodeNs(vcd), from_sr);
    EXPECT_EQ(decodeNs(csv), from_sr);
}
