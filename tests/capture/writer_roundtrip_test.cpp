// write -> read round trips: a random Waveform written as VCD and as each CSV dialect
// reads back with the same initial levels and edges.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <random>

#include <zip.h>

#include "capture/capture_writer.h"
#include "capture_util.h"
#include "core/waveform.h"

namespace busdecode::test {
namespace {

Waveform randomWave(Timebase tb, std::uint32_t seed, int edges_per_line, Tick max_gap) {
    std::mt19937 rng(seed);
    std::vector<std::string> names = {"clk", "data", "cs"};
    std::vector<std::uint8_t> init = {1, 0, 1};
    WaveBuilder b(tb, names, init);
    // lines share some instants, so one timestamp carries several changes
    Tick t = 0;
    std::uniform_int_distribution<Tick> gap(0, max_gap);
    std::uniform_int_distribution<int> line(0, 2);
    for (int i = 0; i < edges_per_line * 3; ++i) {
        t += gap(rng);
        const auto l = std::uint32_t(line(rng));
        b.set(l, t, !b.level(l));
    }
    return b.build(t + 7);
}

// Edges of the file read back, on the lines in Waveform order, in ns.
std::vector<NsEdge> wantNs(const Waveform& w) {
    std::vector<NsEdge> out;
    for (const Edge& e : w.edges)
        out.push_back({w.timebase.toNs(e.t), std::uint32_t(e.line), int(e.level)});
    return out;
}

void expectSameNs(const std::vector<NsEdge>& got, const std::vector<NsEdge>& want,
                  std::int64_t tol) {
    ASSERT_EQ(got.size(), want.size());
    for (std::size_t i = 0; i < got.size(); ++i) {
        ASSERT_EQ(got[i].line, want[i].line) << i;
        ASSERT_EQ(got[i].level, want[i].level) << i;
        ASSERT_LE(std::llabs(got[i].ns - want[i].ns), tol) << i;
    }
}

TEST(WriterRoundTrip, VcdExactTimescale) {
    for (Timebase tb :
         {Timebase{1, 1'000'000'000}, Timebase{100, 1'000'000'000'000}, Timebase{10, 1'000'000}}) {
        auto w = randomWave(tb, 7, 3000, 40);
        const std::string p = tempDir() + "/rt.vcd";
        writeVcd(w, p);
        auto c = collectFile(p, {"clk", "data", "cs"});
        EXPECT_EQ(c.tb.num * w.timebase.den, w.timebase.num * c.tb.den);
        EXPECT_EQ(c.signals[0].full_name, "busdecode.clk");
        EXPECT_EQ(c.initial, w.initial);
        EXPECT_EQ(c.start, w.start);
        EXPECT_EQ(c.end, w.end);
        EXPECT_EQ(c.edges, w.edges);
    }
}

TEST(WriterRoundTrip, VcdSampleRateTimebaseGoesThroughPicoseconds) {
    auto w = randomWave(Timebase::fromSampleRate(24'000'000), 11, 2000, 30);
    const std::string p = tempDir() + "/rt24.vcd";
    writeVcd(w, p);
    auto c = collectFile(p, {"clk", "data", "cs"});
    EXPECT_EQ(c.tb.den, 1'000'000'000'000);
    EXPECT_EQ(c.initial, w.initial);
    expectSameNs(inNs(c), wantNs(w), 0);
}

TEST(WriterRoundTrip, SigrokDenseCsv) {
    auto w = randomWave(Timebase::fromSampleRate(2'500'000), 3, 1500, 9);
    const std::string p = tempDir() + "/rt_sigrok.csv";
    writeCsv(w, p, CsvDialect::SigrokDense);
    auto c = collectFile(p, {"clk", "data", "cs"});
    EXPECT_EQ(c.format, "sigrok-csv");
    EXPECT_EQ(c.tb.den, 2'500'000);
    EXPECT_EQ(c.initial, w.initial);
    EXPECT_EQ(c.end, w.end);
    EXPECT_EQ(c.edges, w.edges);
}

TEST(WriterRoundTrip, PlainCsvWithRate) {
    auto w = randomWave(Timebase::fromSampleRate(1000), 5, 1000, 9);
    const std::string p = tempDir() + "/rt_plain.csv";
    writeCsv(w, p, CsvDialect::Plain);
    OpenOptions o;
    o.rate_hz = 1000;
    auto c = collectFile(p, {"clk", "data", "cs"}, o);
    EXPECT_EQ(c.format, "plain-csv");
    EXPECT_EQ(c.initial, w.initial);
    EXPECT_EQ(c.edges, w.edges);
}

TEST(WriterRoundTrip, SaleaeLogic2Csv) {
    for (Timebase tb : {Timebase{1, 1'000'000'000}, Timebase::fromSampleRate(24'000'000),
                        Timebase{1, 1'000'000}}) {
        auto w = randomWave(tb, 13, 2000, 50);
        const std::string p = tempDir() + "/rt_saleae.csv";
        writeCsv(w, p, CsvDialect::SaleaeLogic2);
        auto c = collectFile(p, {"clk", "data", "cs"});
        EXPECT_EQ(c.format, "saleae-csv");
        EXPECT_EQ(c.initial, w.initial);
        EXPECT_EQ(c.tb.toNs(c.end), w.timebase.toNs(w.end));
        expectSameNs(inNs(c), wantNs(w), 0);
    }
}

// A sigrok session of 1 to 64 lines (unitsize 1 to 8) reads back sample for sample; the
// longer ones span several 4 MiB chunks, which hold whole samples (4 MiB is no multiple
// of a 3-byte sample).
TEST(WriterRoundTrip, SigrokSession) {
    std::mt19937 rng(5);
    for (int lines : {1, 4, 8, 9, 17, 24, 32, 34, 64}) {
        SCOPED_TRACE(lines);
        std::vector<std::string> names;
        std::vector<std::uint8_t> init;
        for (int i = 0; i < lines; ++i) {
            names.push_back("D" + std::to_string(i) + (i == 2 ? " with blanks" : ""));
            init.push_back(std::uint8_t(rng() & 1));
        }
        WaveBuilder b(Timebase::fromSampleRate(50'000'000), names, init);
        const Tick span = lines >= 17 && lines <= 24 ? 3'000'000 : 200'000;  // 3 bytes a sample
        Tick t = 0;
        while (t < span) {
            t += Tick(rng() % 3000);
            const auto l = std::uint32_t(rng() % unsigned(lines));
            b.set(l, t, !b.level(l));
        }
        const Waveform w = b.build(t + 11);
        const std::string p = tempDir() + "/rt.sr";
        writeSr(w, p);
        auto c = collectFile(p);
        EXPECT_EQ(c.format, "sigrok-sr");
        ASSERT_EQ(c.signals.size(), std::size_t(lines));
        EXPECT_EQ(c.signals[lines - 1].name, names.back());
        EXPECT_EQ(c.tb.den, 50'000'000);
        EXPECT_EQ(c.initial, w.initial);
        EXPECT_EQ(c.start, 0);
        EXPECT_EQ(c.end, w.end);
        EXPECT_EQ(c.edges, w.edges);

        int err = 0;
        zip_t* z = zip_open(p.c_str(), ZIP_RDONLY, &err);
        ASSERT_NE(z, nullptr);
        const std::uint64_t unit = std::uint64_t(lines + 7) / 8, samples = std::uint64_t(w.end) + 1;
        const std::uint64_t per_chunk = (4u << 20) / unit;
        const std::uint64_t chunks = (samples + per_chunk - 1) / per_chunk;
        EXPECT_EQ(zip_get_num_entries(z, 0), zip_int64_t(2 + chunks));  // + version, metadata
        zip_stat_t st;
        ASSERT_EQ(zip_stat(z, "logic-1-1", 0, &st), 0);
        EXPECT_EQ(st.size, std::min(samples, per_chunk) * unit);
        EXPECT_EQ(zip_stat(z, ("logic-1-" + std::to_string(chunks + 1)).c_str(), 0, &st), -1);
        zip_discard(z);
    }
}

// Samples deflate cannot shrink (eight lines random at every sample) read back exactly.
TEST(WriterRoundTrip, SigrokSessionOfNoise) {
    std::mt19937 rng(9);
    std::vector<std::string> names;
    for (int i = 0; i < 8; ++i)
        names.push_back("N" + std::to_string(i));
    WaveBuilder b(Timebase::fromSampleRate(1'000'000), names, std::vector<std::uint8_t>(8, 0));
    for (Tick t = 1; t < 300'000; ++t) {
        const std::uint32_t bits = rng();
        for (std::uint32_t l = 0; l < 8; ++l)
            b.set(l, t, (bits >> l) & 1);
    }
    const Waveform w = b.build(300'000);
    const std::string p = tempDir() + "/noise.sr";
    writeSr(w, p);
    auto c = collectFile(p);
    EXPECT_EQ(c.initial, w.initial);
    EXPECT_EQ(c.end, w.end);
    ASSERT_EQ(c.edges.size(), w.edges.size());
    EXPECT_TRUE(c.edges == w.edges);
}

// The renderer's stretches, in order and out of it, give the samples of one pass.
TEST(Writer, SampleRendererStretchesInAnyOrder) {
    WaveBuilder b(Timebase::fromSampleRate(1'000'000),
                  {"A", "B", "C", "D", "E", "F", "G", "H", "I"}, {1, 0, 1, 0, 0, 0, 0, 0, 1});
    std::mt19937 rng(3);
    for (Tick t = 1; t < 5000; t += Tick(rng() % 7))
        b.set(rng() % 9, t, rng() & 1);
    const Waveform w = b.build(5000);
    SampleRenderer once(w);
    ASSERT_EQ(once.unit(), 2u);
    std::vector<std::uint8_t> want(5001 * 2), got(5001 * 2);
    once.render(0, 5001, want.data());
    EXPECT_EQ(want[0], 0b00000101);  // A and C high
    EXPECT_EQ(want[1], 0b00000001);  // I high
    SampleRenderer parts(w);
    parts.render(3000, 2001, got.data() + 3000 * 2);  // the end first
    parts.render(0, 1000, got.data());                // then earlier: starts over
    parts.render(1000, 2000, got.data() + 1000 * 2);  // and on from there
    EXPECT_EQ(got, want);
}

TEST(Writer, SigrokSessionErrors) {
    WaveBuilder b(Timebase::fromSampleRate(1'000'000), {"A"}, {0});
    const Waveform w = b.build(10);
    const std::string bad = tempDir() + "/no/such/dir/x.sr";
    try {
        writeSr(w, bad);
        FAIL() << "no error";
    } catch (const InputError& e) {
        EXPECT_EQ(std::string(e.what()).rfind(bad + ": cannot write", 0), 0u) << e.what();
    }
    EXPECT_FALSE(std::filesystem::exists(bad));
    WaveBuilder wide(Timebase::fromSampleRate(1'000'000), std::vector<std::string>(65, "x"),
                     std::vector<std::uint8_t>(65, 0));
    EXPECT_THROW(writeSr(wide.build(10), tempDir() + "/wide.sr"), std::invalid_argument);
    WaveBuilder ns(Timebase{3, 1'000'000'000}, {"A"}, {0});  // not a whole sample rate
    EXPECT_THROW(writeSr(ns.build(10), tempDir() + "/ns.sr"), std::invalid_argument);
}

TEST(Writer, AtomicNoTemporaryLeftAndUnwritableIsAnError) {
    auto w = randomWave(Timebase{1, 1'000'000'000}, 1, 10, 5);
    const std::string dir = tempDir() + "/atomic";
    std::filesystem::create_directories(dir);
    writeVcd(w, dir + "/a.vcd");
    writeCsv(w, dir + "/a.csv", CsvDialect::SaleaeLogic2);
    int files = 0;
    for (auto& e : std::filesystem::directory_iterator(dir)) {
        ++files;
        EXPECT_EQ(e.path().string().find(".tmp-"), std::string::npos);
    }
    EXPECT_EQ(files, 2);
    EXPECT_THROW(writeVcd(w, dir + "/no/such/dir/a.vcd"), InputError);
    w.timebase = Timebase{3, 10};  // 0.3 s per tick is not a whole sample rate
    EXPECT_THROW(writeCsv(w, dir + "/x.csv", CsvDialect::SigrokDense), std::invalid_argument);
    EXPECT_FALSE(std::filesystem::exists(dir + "/x.csv"));
}

}  // namespace
}  // namespace busdecode::test
