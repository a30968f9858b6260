// FST through fstapi: GTKWave's example files read as the VCD that fst2vcd makes of them
// (the same signals, times, initial levels and edges), generated traffic written as FST
// read as its VCD, and broken files refused with one line naming the file.
#include <gtest/gtest.h>

#include <cstdlib>

#include "capture/capture_writer.h"
#include "capture_util.h"
#include "core/options.h"
#include "core/waveform.h"
#include "random_traffic.h"

namespace busdecode::test {
namespace {

std::string realFst(const std::string& name) {
    return sourceDir() + "/tests/data/real/formats/fst/" + name;
}

// fst2vcd's VCD of `fst`, or "" when fst2vcd is not installed.
std::string viaFst2vcd(const std::string& fst, const std::string& stem) {
    if (std::system("command -v fst2vcd >/dev/null 2>&1") != 0) return "";
    const std::string vcd = tempDir() + "/" + stem + ".vcd";
    const std::string cmd = "fst2vcd '" + fst + "' > '" + vcd + "' 2>/dev/null";
    EXPECT_EQ(std::system(cmd.c_str()), 0) << cmd;
    return vcd;
}

void expectSame(const Collected& fst, const Collected& vcd) {
    EXPECT_EQ(fst.format, "fst");
    ASSERT_EQ(fst.signals.size(), vcd.signals.size());
    for (std::size_t i = 0; i < fst.signals.size(); ++i) {
        EXPECT_EQ(fst.signals[i].full_name, vcd.signals[i].full_name) << i;
        EXPECT_EQ(fst.signals[i].name, vcd.signals[i].name) << i;
        EXPECT_EQ(fst.signals[i].width, vcd.signals[i].width) << i;
    }
    EXPECT_DOUBLE_EQ(fst.tb.secondsPerTick(), vcd.tb.secondsPerTick());
    EXPECT_EQ(fst.start, vcd.start);
    EXPECT_EQ(fst.end, vcd.end);
    EXPECT_EQ(fst.initial, vcd.initial);
    ASSERT_EQ(fst.edges.size(), vcd.edges.size());
    EXPECT_TRUE(fst.edges == vcd.edges);
}

TEST(FstReader, DesMatchesFst2vcd) {
    const std::string vcd = viaFst2vcd(realFst("des.fst"), "des");
    if (vcd.empty()) GTEST_SKIP() << "fst2vcd (Debian gtkwave) is not installed";
    // Scalars, single bits of vectors (both ends, LSB first), nested scopes, an integer.
    const std::vector<std::string> lines = {"top.clk",         "top.des.clk",   "top.ct[0]",
                                            "top.ct[63]",      "top.key[5]",    "top.pt[17]",
                                            "top.i[0]",        "top.i[3]",      "top.des.r9x[0]",
                                            "top.des.r9x[31]", "top.des.l8x[7]"};
    const Collected f = collectFile(realFst("des.fst"), lines);
    const Collected v = collectFile(vcd, lines);
    expectSame(f, v);
    EXPECT_GT(f.edges.size(), 1000u);
}

TEST(FstReader, GzipWrappedTransactionMatchesFst2vcd) {
    const std::string vcd = viaFst2vcd(realFst("transaction.fst"), "transaction");
    if (vcd.empty()) GTEST_SKIP() << "fst2vcd (Debian gtkwave) is not installed";
    std::vector<std::string> lines;
    for (int b = 0; b < 8; ++b)
        lines.push_back("top.val[" + std::to_string(b) + "]");
    const Collected f = collectFile(realFst("transaction.fst"), lines);
    expectSame(f, collectFile(vcd, lines));
    EXPECT_EQ(f.tb.den, 1000);
    EXPECT_GT(f.edges.size(), 100u);
}

TEST(FstReader, UnknownStatesAndRealsAsTheVcdReaderHasThem) {
    // Made by GTKWave's vcd2fst: x and z in a vector, a real, two scalars.
    const std::string fst = sourceDir() + "/fuzz/seeds/fst/small.fst";
    const std::string vcd = viaFst2vcd(fst, "small");
    if (vcd.empty()) GTEST_SKIP() << "fst2vcd (Debian gtkwave) is not installed";
    std::vector<std::string> lines = {"top.clk", "top.cs", "top.v"};
    for (int b = 0; b < 8; ++b)
        lines.push_back("top.data[" + std::to_string(b) + "]");
    const Collected f = collectFile(fst, lines);
    expectSame(f, collectFile(vcd, lines));
    // The count of changes to x or z on the mapped lines, as the VCD reader counts them.
    auto r = openCapture(fst, {}), v = openCapture(vcd, {});
    collect(*r, {{2, 3}, {2, 0}, {3, -1}});
    collect(*v, {{2, 3}, {2, 0}, {3, -1}});
    ASSERT_EQ(r->notes().size(), 1u);
    EXPECT_EQ(r->notes(), v->notes());
}

Waveform traffic(Timebase tb) {
    // Several edge blocks, so hand-offs are exercised.
    Waveform w = randomTraffic(tb, 5, 60000, 30, 40, 11);
    w.start = 3;
    return w;
}

TEST(FstReader, WrittenTrafficReadsAsItsVcd) {
    // 12.5 MHz: an 80 ns tick in 10 ns units; 1 ns; and 3 MHz, rounded to femtoseconds.
    for (const Timebase tb : {Timebase::fromSampleRate(12'500'000), Timebase{1, 1'000'000'000},
                              Timebase::fromSampleRate(3'000'000)}) {
        SCOPED_TRACE(tb.den);
        const Waveform w = traffic(tb);
        const std::string vcd = tempDir() + "/t.vcd", fst = tempDir() + "/t.fst";
        writeVcd(w, vcd);
        writeFst(w, fst);
        const Collected want = collectFile(vcd, {"clk", "data", "cs"});
        const Collected got = collectFile(fst, {"clk", "data", "cs"});
        EXPECT_EQ(got.format, "fst");
        EXPECT_EQ(got.initial, want.initial);
        EXPECT_EQ(got.signals[1].full_name, "busdecode.data");
        const auto a = inNs(got), b = inNs(want);
        ASSERT_EQ(a.size(), b.size());
        for (std::size_t i = 0; i < a.size(); ++i) {
            ASSERT_EQ(a[i].line, b[i].line) << i;
            ASSERT_EQ(a[i].level, b[i].level) << i;
            ASSERT_NEAR(double(a[i].ns), double(b[i].ns), 1.0) << i;
        }
        EXPECT_NEAR(double(got.tb.toNs(got.end)), double(want.tb.toNs(want.end)), 1.0);
    }
}

TEST(FstReader, RateOverridesTheTimescale) {
    OpenOptions opts;
    opts.rate_hz = 1e6;
    const Collected c = collectFile(realFst("transaction.fst"), {"top.val[0]"}, opts);
    EXPECT_EQ(c.tb.num, 1);
    EXPECT_EQ(c.tb.den, 1'000'000);
}

TEST(FstReader, StoppingEarlyEndsTheReadingThread) {
    const Waveform w = traffic(Timebase{1, 1'000'000'000});
    const std::string fst = tempDir() + "/early.fst";
    writeFst(w, fst);
    auto r = openCapture(fst, {});
    r->select({{0, -1}, {1, -1}});
    r->initialLevels();
    EdgeBlock b;
    ASSERT_TRUE(r->next(b));
    r.reset();  // with blocks still queued and the thread waiting: must not hang or leak
}

TEST(FstReader, BrokenFilesAreOneLineNamingTheFile) {
    const std::string good = readFile(realFst("des.fst"));
    for (std::size_t cut :
         {std::size_t(5), std::size_t(200), std::size_t(400), good.size() / 2, good.size() - 1}) {
        SCOPED_TRACE(cut);
        const std::string p = tempCapture("cut.fst", good.substr(0, cut));
        const std::string e = errorOf(p);
        EXPECT_EQ(e.rfind(p + ": ", 0), 0u) << e;
        EXPECT_EQ(e.find('\n'), std::string::npos) << e;
    }
    std::string p = tempCapture("cut2.fst", good.substr(0, good.size() / 2));
    EXPECT_NE(errorOf(p).find("(truncated)"), std::string::npos) << errorOf(p);
    std::string bad = good;
    bad[0] = char(0xff);  // the header still being written: a killed simulation
    p = tempCapture("unfinished.fst", bad);
    EXPECT_EQ(errorOf(p), p + ": unfinished FST file (its writer never closed it)");
    bad = good;
    bad[329 + 1] = char(0x42);  // the second block's type
    p = tempCapture("type.fst", bad);
    EXPECT_NE(errorOf(p).find(p + ": FST block 1 at byte 330: type 66"), std::string::npos)
        << errorOf(p);
    const std::string wrapped = readFile(realFst("transaction.fst"));
    p = tempCapture("wrapped_cut.fst", wrapped.substr(0, wrapped.size() - 40));
    EXPECT_NE(errorOf(p).find(p + ": its gzip wrapper says"), std::string::npos) << errorOf(p);
}

TEST(FstReader, FromStandardInputAndCompressed) {
    const std::string fst = realFst("transaction.fst");
    const std::string gz = tempDir() + "/t.fst.gz";
    compressFile(fst, gz, Compression::Gzip);
    const Collected a = collectFile(fst, {"top.val[2]"});
    const Collected b = collectFile(gz, {"top.val[2]"});
    EXPECT_EQ(b.format, "fst+gzip");
    EXPECT_TRUE(a.edges == b.edges);
    const auto r =
        runCommand(shellQuote(binDir() + "/decode") + " --formats - < " + shellQuote(gz));
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find("-: fst+gzip, timebase 1/1000 s, 1 signals"), std::string::npos) << r.out;
}

TEST(FstReader, DecodeExitsTwoWithOneLine) {
    const std::string good = readFile(realFst("des.fst"));
    const std::string p = tempCapture("half.fst", good.substr(0, good.size() / 2));
    const auto r = runDecode({"--formats", p});
    EXPECT_EQ(r.status, 2);
    EXPECT_EQ(r.err.rfind("decode: " + p + ": FST block ", 0), 0u) << r.err;
    EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << r.err;
}

}  // namespace
}  // namespace busdecode::test
