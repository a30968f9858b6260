// DSView sessions (.dsl): real demo sessions read as DSView shows them (their bit-planes
// scanned sample by sample here as the reference), generated traffic written by
// writeDsl() read back edge for edge across blocks, and broken sessions refused with one
// line naming the file and the block.
#include <gtest/gtest.h>

#include <zip.h>

#include <fmt/format.h>

#include "capture/capture_writer.h"
#include "capture_util.h"
#include "core/waveform.h"
#include "zip_builder.h"

namespace busdecode::test {
namespace {

std::string realDsview(const std::string& file) {
    return sourceDir() + "/tests/data/real/formats/dsview/" + file;
}

std::string member(const std::string& path, const std::string& name) {
    int err = 0;
    zip_t* z = zip_open(path.c_str(), ZIP_RDONLY, &err);
    EXPECT_NE(z, nullptr);
    zip_stat_t st;
    EXPECT_EQ(zip_stat(z, name.c_str(), 0, &st), 0) << name;
    std::string out(st.size, '\0');
    zip_file_t* f = zip_fopen(z, name.c_str(), 0);
    EXPECT_EQ(zip_fread(f, out.data(), out.size()), zip_int64_t(out.size()));
    zip_fclose(f);
    zip_discard(z);
    return out;
}

// The reference: one sample at a time from a one-block plane.
std::vector<Edge> planeEdges(const std::string& plane, std::uint32_t line, std::uint64_t samples,
                             std::uint8_t& initial) {
    std::vector<Edge> out;
    auto bit = [&](std::uint64_t k) { return std::uint8_t((plane[k / 8] >> (k % 8)) & 1); };
    initial = bit(0);
    std::uint8_t level = initial;
    for (std::uint64_t k = 1; k < samples; ++k)
        if (bit(k) != level) out.push_back(Edge(Tick(k), line, level = bit(k)));
    return out;
}

TEST(DslReader, ProtocolDemoMatchesItsPlanes) {
    const std::string p = realDsview("protocol.demo");
    const Collected c = collectFile(p);
    ASSERT_EQ(c.signals.size(), 16u);
    EXPECT_EQ(c.signals[5].name, "UART");
    EXPECT_EQ(c.signals[13].name, "CS#");
    EXPECT_EQ(c.format, "dsview-dsl");
    EXPECT_EQ(c.tb.den / c.tb.num, 25'000'000);
    EXPECT_EQ(c.end, 131071);
    std::vector<Edge> want;
    for (std::uint32_t l = 0; l < 16; ++l) {
        std::uint8_t initial = 0;
        const auto e = planeEdges(member(p, "L-" + std::to_string(l) + "/0"), l, 131072, initial);
        EXPECT_EQ(c.initial[l], initial) << l;
        want.insert(want.end(), e.begin(), e.end());
    }
    std::stable_sort(want.begin(), want.end(), [](const Edge& a, const Edge& b) {
        return a.t != b.t ? a.t < b.t : a.line < b.line;
    });
    ASSERT_GT(want.size(), 1000u);
    EXPECT_EQ(c.edges, want);
}

TEST(DslReader, ProtocolDemoUartText) {
    const auto r = runDecode({realDsview("protocol.demo"), "--proto", "uart", "--map", "rx=UART",
                              "--opt", "baud=115200", "--format", "jsonl"});
    ASSERT_EQ(r.status, 0) << r.err;
    std::string text;
    for (std::size_t at = r.out.find("\"value\":"); at != std::string::npos;
         at = r.out.find("\"value\":", at + 1))
        text += char(std::stoi(r.out.substr(at + 8)));
    EXPECT_NE(text.find("DSLogic series USB-based LA from DreamSourceLab"), std::string::npos)
        << text;
}

TEST(DslReader, SpiDemoAcrossTenBlocks) {
    const auto r = runDecode({realDsview("demo_spi.dsl"), "--proto", "spi", "--map", "sclk=clk",
                              "--map", "mosi=mosi", "--map", "miso=miso", "--map", "cs=cs", "--opt",
                              "bits=8", "--format", "jsonl"});
    ASSERT_EQ(r.status, 0) << r.err;
    // 566 chip-select frames of three bytes, none cut short.
    std::size_t words = 0;
    for (std::size_t at = r.out.find("\"type\":\"transfer\""); at != std::string::npos;
         at = r.out.find("\"type\":\"transfer\"", at + 1))
        ++words;
    EXPECT_EQ(words, 3u * 566u);
    EXPECT_EQ(r.out.find("short_frame"), std::string::npos);
}

// DSView draws a higher code as a lower voltage: a code below the channel's offset is high.
TEST(DslReader, DsoSquareEdgesWhereItsCodesChange) {
    const std::string path = realDsview("demo_square_dso.dsl");
    const Collected got = collectFile(path);
    EXPECT_EQ(got.format, "dsview-dsl-dso");
    ASSERT_EQ(got.signals.size(), 2u);
    EXPECT_EQ(got.signals[0].name, "0");
    const auto ns = inNs(got);
    for (std::uint32_t ch = 0; ch < 2; ++ch) {
        SCOPED_TRACE(ch);
        const std::string codes = member(path, fmt::format("O-{}/0", ch));
        ASSERT_EQ(codes.size(), 10000u);
        std::vector<std::pair<std::uint64_t, int>> want;  // sample, level after
        for (std::size_t k = 1; k < codes.size(); ++k)
            if (codes[k] != codes[k - 1]) want.push_back({k, std::uint8_t(codes[k]) < 128 ? 1 : 0});
        EXPECT_EQ(got.initial[ch], std::uint8_t(codes[0]) < 128 ? 1 : 0);
        std::vector<NsEdge> mine;
        for (const NsEdge& e : ns)
            if (e.line == ch) mine.push_back(e);
        ASSERT_EQ(mine.size(), want.size());
        for (std::size_t i = 0; i < want.size(); ++i) {
            EXPECT_EQ(mine[i].level, want[i].second) << i;
            // 100 MHz: the crossing lies within the 10 ns before the sample that shows it.
            EXPECT_NEAR(double(mine[i].ns), double(want[i].first) * 10 - 5, 5) << i;
        }
    }
}

TEST(DslReader, AnalogSineCrossesItsMiddleWhereItsCodesDo) {
    const std::string path = realDsview("demo_sine_analog.dsl");
    const Collected got = collectFile(path);
    EXPECT_EQ(got.format, "dsview-dsl-analog");
    ASSERT_EQ(got.signals.size(), 2u);
    const std::string codes = member(path, "A-0/0");
    ASSERT_EQ(codes.size(), 244u);  // 122 samples of 2 channels, interleaved
    // Where channel 0's codes pass the middle (128), one sample period (100 ms) wide.
    std::vector<double> crossings_ns;
    for (std::size_t k = 1; k < 122; ++k) {
        const int a = std::uint8_t(codes[2 * (k - 1)]) - 128, b = std::uint8_t(codes[2 * k]) - 128;
        if ((a < 0 && b >= 0) || (a > 0 && b <= 0)) crossings_ns.push_back(double(k) * 1e8);
    }
    ASSERT_EQ(crossings_ns.size(), 2u);
    for (std::uint32_t ch = 0; ch < 2; ++ch) {
        std::vector<NsEdge> mine;
        for (const NsEdge& e : inNs(got))
            if (e.line == ch) mine.push_back(e);
        // Code 128 first (0 V), then rising codes: a falling voltage, low from the start.
        EXPECT_EQ(got.initial[ch], 0);
        ASSERT_EQ(mine.size(), 2u) << ch;
        EXPECT_EQ(mine[0].level, 1);
        EXPECT_EQ(mine[1].level, 0);
        for (std::size_t i = 0; i < 2; ++i)
            EXPECT_NEAR(double(mine[i].ns), crossings_ns[i] - 5e7, 1e8) << ch << " " << i;
    }
}

Waveform sparseTraffic(Tick samples) {
    WaveBuilder b(Timebase::fromSampleRate(100'000'000), {"clk", "data", "cs"}, {1, 0, 1});
    std::uint64_t x = 12345;
    Tick t = 0;
    while (true) {
        x = x * 6364136223846793005ULL + 1442695040888963407ULL;
        t += 1 + Tick((x >> 33) % 200000);
        if (t >= samples - 1) break;
        b.set(std::uint32_t((x >> 20) % 3), t, !b.level(std::uint32_t((x >> 20) % 3)));
    }
    // Changes around a block boundary and on the last sample.
    for (Tick at : {Tick(1 << 24) - 1, Tick(1 << 24), Tick(1 << 24) + 1, samples - 1})
        if (at > t) b.set(0, t = at, !b.level(0));
    return b.build(samples - 1);
}

TEST(DslReader, RoundTripAcrossBlocks) {
    const Waveform w = sparseTraffic(Tick(1 << 24) * 2 + 1000);  // two full blocks and a bit
    const std::string p = tempDir() + "/rt.dsl";
    writeDsl(w, p);
    const Collected c = collectFile(p, {"clk", "data", "cs"});
    EXPECT_EQ(c.initial, w.initial);
    EXPECT_EQ(c.edges, w.edges);
    EXPECT_EQ(c.end, w.end);
    // The same traffic as a VCD gives the same events.
    const std::string vcd = tempDir() + "/rt.vcd";
    writeVcd(w, vcd);
    EXPECT_EQ(inNs(collectFile(vcd, {"clk", "data", "cs"})), inNs(c));
}

std::string header(const std::string& samples, const std::string& blocks,
                   const std::string& extra = "samplerate = 1 MHz\n") {
    return "[version]\nversion = 2\n[header]\ndevice mode = 0\ntotal samples = " + samples +
           "\ntotal probes = 1\ntotal blocks = " + blocks + "\n" + extra + "probe0 = a\n";
}

TEST(DslReader, BrokenSessions) {
    const std::string full(1 << 21, '\x55');
    auto session = [&](const std::string& name,
                       const std::vector<std::pair<std::string, std::string>>& m) {
        return tempCapture(name, fuzz::buildStoredZip(m));
    };
    std::string p = session("size.dsl", {{"header", header("20000000", "2")},
                                         {"L-0/0", full.substr(0, 1000)},
                                         {"L-0/1", full.substr(0, 1000)}});
    EXPECT_EQ(errorOf(p), p + ": block L-0/0 holds 1000 bytes, a full block holds 2097152 "
                              "(wrong block size)");
    p = session("missing.dsl", {{"header", header("20000000", "2")}, {"L-0/0", full}});
    EXPECT_EQ(errorOf(p), p + ": block L-0/1 is missing");
    p = session("blocks.dsl", {{"header", header("100", "3")}, {"L-0/0", full.substr(0, 16)}});
    EXPECT_EQ(errorOf(p), p + ": header: total blocks = 3, but 100 samples take 1 blocks of 2^24");
    p = session("rate.dsl", {{"header", header("100", "1", "")}, {"L-0/0", full.substr(0, 16)}});
    EXPECT_EQ(errorOf(p), p + ": header has no samplerate (not a DSView session?)");
    p = session("count.dsl", {{"header", header("1x", "1")}, {"L-0/0", full.substr(0, 16)}});
    EXPECT_EQ(errorOf(p), p + ": header: total samples = '1x' is not a count");
    // A real session cut short: its central directory is gone.
    const std::string bytes = readFile(realDsview("protocol.demo"));
    p = tempCapture("cut.dsl", bytes.substr(0, bytes.size() / 2));
    EXPECT_EQ(errorOf(p).rfind(p + ": not a readable ZIP capture", 0), 0u) << errorOf(p);
    // Deflated data damaged: the block is named.
    std::string bad = bytes;
    const auto at = bad.find("L-5/0");
    ASSERT_NE(at, std::string::npos);
    for (std::size_t i = at + 40; i < at + 200; ++i)
        bad[i] = char(bad[i] ^ 0x5a);
    p = tempCapture("bad.dsl", bad);
    EXPECT_NE(errorOf(p).find("L-5/0"), std::string::npos) << errorOf(p);
}

TEST(DslReader, BrokenDsoAndAnalogSessionsNameTheBlock) {
    const std::string dso = realDsview("demo_square_dso.dsl");
    const std::string head = member(dso, "header"), codes = member(dso, "O-0/0");
    auto session = [&](const std::string& name,
                       const std::vector<std::pair<std::string, std::string>>& m) {
        return tempCapture(name, fuzz::buildStoredZip(m));
    };
    std::string p = session("dso_short.dsl",
                            {{"header", head}, {"O-0/0", codes}, {"O-1/0", codes.substr(0, 9000)}});
    EXPECT_EQ(errorOf(p), p + ": block O-1/0 holds 9000 bytes, 10000 samples take 10000 "
                              "(wrong block size)");
    p = session("dso_missing.dsl", {{"header", head}, {"O-0/0", codes}});
    EXPECT_EQ(errorOf(p), p + ": block O-1/0 is missing");
    const std::string sine = realDsview("demo_sine_analog.dsl");
    const std::string ahead = member(sine, "header"), rows = member(sine, "A-0/0");
    p = session("analog_odd.dsl", {{"header", ahead}, {"A-0/0", rows.substr(0, 243)}});
    EXPECT_EQ(errorOf(p), p + ": block A-0/0 holds 243 bytes, not whole rows of 2 channels "
                              "(wrong block size)");
    p = session("analog_short.dsl", {{"header", ahead}, {"A-0/0", rows.substr(0, 200)}});
    EXPECT_EQ(errorOf(p), p + ": the A-0 blocks hold 100 samples, the header says total "
                              "samples = 122 (wrong block size)");
    std::string bits = ahead;
    bits.replace(bits.find("bits = 8"), 8, "bits = 16");
    p = session("analog_bits.dsl", {{"header", bits}, {"A-0/0", rows}});
    EXPECT_EQ(errorOf(p), p + ": header: bits = 16: only 8-bit samples are read");
    // Deflated samples damaged: the block is named.
    std::string bad = readFile(dso);
    const auto at = bad.find("O-1/0");
    ASSERT_NE(at, std::string::npos);
    for (std::size_t i = at + 40; i < at + 120 && i < bad.size(); ++i)
        bad[i] = char(bad[i] ^ 0x5a);
    p = tempCapture("dso_bad.dsl", bad);
    EXPECT_NE(errorOf(p).find("O-1/0"), std::string::npos) << errorOf(p);
}

}  // namespace
}  // namespace busdecode::test
