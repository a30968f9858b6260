// Golden tests: our SPI decoder against sigrok's expected outputs (sigrok-test
// decoder/test/spi and adf435x) on the real captures of sigrok-dumps. Every data word
// must agree in value *and* sample range (ticks of a .sr capture are samples).
#include <gtest/gtest.h>

#include <fstream>
#include <regex>
#include <sstream>

#include "capture/capture_reader.h"
#include "core/registry.h"
#include "core/session.h"
#include "spi_info.h"
#include "support/decode_events.h"
#include "support/paths.h"

using namespace busdecode;
using namespace busdecode::test;

namespace {

std::vector<Event> decodeSr(const std::string& rel, std::map<std::string, std::string> map,
                            std::map<std::string, std::string> opts) {
    Registry::instance().add(makeSpiFactory());
    const std::string path = realCaptures() + "/sigrok-dumps/spi/" + rel;
    return decodeEvents(path, {DecoderRequest{"spi", std::move(map), std::move(opts)}});
}

// One expected word: sample range and the hex texts of sigrok's data annotations.
struct Word {
    Tick ss = 0, es = 0;
    std::string mosi, miso;  // hex, empty when sigrok did not annotate that line
};

std::string expectedDir() {
    return realCaptures() + "/sigrok-test/decoder/test/";
}

// `<ss>-<es> spi: mosi-data: "E2"` lines (miso-data likewise), merged by sample range.
std::vector<Word> readDataAnnotations(const std::string& file) {
    std::ifstream in(expectedDir() + file);
    EXPECT_TRUE(in.good()) << file;
    std::vector<Word> out;
    std::regex re(R"(^(\d+)-(\d+) spi: (mosi|miso)-data: \"([0-9A-F]+)\"$)");
    std::string line;
    while (std::getline(in, line)) {
        std::smatch m;
        if (!std::regex_match(line, m, re)) continue;
        Tick ss = std::stoll(m[1]), es = std::stoll(m[2]);
        if (out.empty() || out.back().ss != ss || out.back().es != es)
            out.push_back({ss, es, "", ""});
        (m[3] == "mosi" ? out.back().mosi : out.back().miso) = m[4];
    }
    return out;
}

// `<ss>-<es> spi: ['DATA', mosi, miso]` lines of the .python outputs (decimal or None).
std::vector<Word> readPythonData(const std::string& file) {
    std::ifstream in(expectedDir() + file);
    EXPECT_TRUE(in.good()) << file;
    std::vector<Word> out;
    std::regex re(R"(^(\d+)-(\d+) spi: \['DATA', (None|\d+), (None|\d+)\]$)");
    std::string line;
    while (std::getline(in, line)) {
        std::smatch m;
        if (!std::regex_match(line, m, re)) continue;
        Word w{std::stoll(m[1]), std::stoll(m[2]), "", ""};
        if (m[3] != "None") w.mosi = m[3];
        if (m[4] != "None") w.miso = m[4];
        out.push_back(w);
    }
    return out;
}

std::uint64_t hexValue(const std::string& h) {
    return std::stoull(h, nullptr, 16);
}

// Compares the clean words we decoded with sigrok's; words cut short by cs (which
// sigrok drops silently) are left out of the comparison but must carry short_frame.
void compareWords(const std::vector<Event>& events, const std::vector<Word>& want,
                  bool decimal = false) {
    std::vector<Event> words;
    for (const auto& e : events) {
        if (e.hasError("short_frame")) continue;
        EXPECT_TRUE(e.errors.empty()) << e.summary;
        words.push_back(e);
    }
    ASSERT_EQ(words.size(), want.size());
    ASSERT_FALSE(want.empty());
    auto value = [&](const std::string& s) { return decimal ? std::stoull(s) : hexValue(s); };
    for (std::size_t i = 0; i < want.size(); ++i) {
        SCOPED_TRACE(i);
        EXPECT_EQ(words[i].start, want[i].ss);
        EXPECT_EQ(words[i].end, want[i].es);
        if (!want[i].mosi.empty()) {
            EXPECT_EQ(std::get<std::uint64_t>(*words[i].get("mosi")), value(want[i].mosi));
        }
        if (!want[i].miso.empty()) {
            EXPECT_EQ(std::get<std::uint64_t>(*words[i].get("miso")), value(want[i].miso));
        }
    }
}

const std::map<std::string, std::string> kMode0 = {{"cpol", "0"}, {"cpha", "0"}};

std::map<std::string, std::string> withBits(int bits, bool lsb = false) {
    auto o = kMode0;
    o["bits"] = std::to_string(bits);
    if (lsb) o["lsb_first"] = "1";
    return o;
}

}  // namespace

TEST(SpiGolden, Adf4351BytesAsSigrokDecodesThem) {
    auto ev = decodeSr("adf4351/set-4000mhz.sr", {{"cs", "0"}, {"mosi", "1"}, {"sclk", "2"}},
                       withBits(8));
    compareWords(ev, readDataAnnotations("spi/adf4351-set-4000mhz.output"));
}

TEST(SpiGolden, Adf4351As32BitRegisterWrites) {
    auto ev = decodeSr("adf4351/set-4000mhz.sr", {{"cs", "0"}, {"mosi", "1"}, {"sclk", "2"}},
                       withBits(32));
    // sigrok decodes bytes; four bytes under one cs are one 32-bit register write,
    // spanning from the first byte's start to the last byte's end.
    auto bytes = readDataAnnotations("spi/adf4351-set-4000mhz.output");
    ASSERT_EQ(bytes.size() % 4, 0u);
    std::vector<Word> regs;
    for (std::size_t i = 0; i < bytes.size(); i += 4)
        regs.push_back({bytes[i].ss, bytes[i + 3].es,
                        bytes[i].mosi + bytes[i + 1].mosi + bytes[i + 2].mosi + bytes[i + 3].mosi,
                        ""});
    compareWords(ev, regs);
    const std::uint64_t want[] = {0x00D80005, 0x008C80FC, 0x000004B3,
                                  0x00004E42, 0x08008011, 0x00500000};
    ASSERT_EQ(ev.size(), 6u);
    for (int i = 0; i < 6; ++i)
        EXPECT_EQ(std::get<std::uint64_t>(*ev[i].get("mosi")), want[i]);
}

TEST(SpiGolden, WordWidth9) {
    auto ev = decodeSr("wordwidths/9bit_spi.sr", {{"cs", "4"}, {"sclk", "2"}, {"mosi", "5"}},
                       withBits(9));
    compareWords(ev, readDataAnnotations("spi/9bit_spi.output"));
}

TEST(SpiGolden, WordWidth16) {
    auto ev = decodeSr("wordwidths/16bit_spi.sr",
                       {{"cs", "12"}, {"sclk", "7"}, {"miso", "9"}, {"mosi", "8"}}, withBits(16));
    compareWords(ev, readDataAnnotations("spi/16bit_spi.output"));
}

TEST(SpiGolden, WordWidth40) {
    auto ev = decodeSr("wordwidths/40bit_spi.sr",
                       {{"cs", "12"}, {"sclk", "7"}, {"miso", "8"}, {"mosi", "9"}}, withBits(40));
    compareWords(ev, readDataAnnotations("spi/40bit_spi.output"));
}

TEST(SpiGolden, WordWidth152IsOverOurLimitAndReportedSanely) {
    // Our words are at most 64 bits: the 152-bit transfer comes out as two 64-bit words
    // and a 24-bit remainder cut short by cs, whose bits are exactly sigrok's word.
    auto ev = decodeSr("wordwidths/152bit_spi.sr",
                       {{"cs", "12"}, {"sclk", "7"}, {"miso", "9"}, {"mosi", "8"}}, withBits(64));
    auto want = readDataAnnotations("spi/152bit_spi.output");
    ASSERT_EQ(want.size(), 1u);
    ASSERT_EQ(want[0].mosi.size(), 38u);
    ASSERT_EQ(ev.size(), 3u);
    const std::size_t cut[] = {0, 16, 32, 38};
    for (int i = 0; i < 3; ++i) {
        SCOPED_TRACE(i);
        EXPECT_EQ(std::get<std::uint64_t>(*ev[i].get("mosi")),
                  hexValue(want[0].mosi.substr(cut[i], cut[i + 1] - cut[i])));
        EXPECT_EQ(std::get<std::uint64_t>(*ev[i].get("miso")),
                  hexValue(want[0].miso.substr(cut[i], cut[i + 1] - cut[i])));
        EXPECT_EQ(asInt(*ev[i].get("bits")), i < 2 ? 64 : 24);
        EXPECT_EQ(ev[i].hasError("short_frame"), i == 2);
    }
    EXPECT_EQ(ev[0].start, want[0].ss);
}

TEST(SpiGolden, CountMosiMsb) {
    auto ev =
        decodeSr("spi-count-msb.sr", {{"cs", "1"}, {"sclk", "0"}, {"mosi", "2"}}, withBits(8));
    compareWords(ev, readDataAnnotations("spi/spi_count_mosi_msb.output"));
}

TEST(SpiGolden, CountMisoMsb) {
    auto ev =
        decodeSr("spi-count-msb.sr", {{"cs", "1"}, {"sclk", "0"}, {"miso", "2"}}, withBits(8));
    compareWords(ev, readDataAnnotations("spi/spi_count_miso_msb.output"));
}

TEST(SpiGolden, CountMosiLsb) {
    auto ev = decodeSr("spi-count-lsb.sr", {{"cs", "1"}, {"sclk", "0"}, {"mosi", "2"}},
                       withBits(8, true));
    compareWords(ev, readDataAnnotations("spi/spi_count_mosi_lsb.output"));
}

TEST(SpiGolden, CountMisoLsb) {
    // sigrok's annotation file for this case is empty (its test.conf asks for the
    // mosi class); its python output carries the words.
    auto ev = decodeSr("spi-count-lsb.sr", {{"cs", "1"}, {"sclk", "0"}, {"miso", "2"}},
                       withBits(8, true));
    compareWords(ev, readPythonData("spi/spi_count_miso_lsb.python"), true);
}

TEST(SpiGolden, Cc1101BurstRead) {
    auto ev = decodeSr("cc1101/cc1101-burst-read.sr",
                       {{"mosi", "0"}, {"miso", "2"}, {"sclk", "1"}, {"cs", "5"}}, withBits(8));
    compareWords(ev, readDataAnnotations("spi/cc1101-burst-read.output"));
}

TEST(SpiGolden, Mx25l1605dProbe) {
    auto ev = decodeSr("mx25l1605d/mx25l1605d_probe.sr",
                       {{"cs", "0"}, {"miso", "1"}, {"sclk", "2"}, {"mosi", "3"}}, withBits(8));
    compareWords(ev, readDataAnnotations("spi/mx25l1605d_probe.output"));
}
