// Text captures with bare-CR line ends (classic Mac exports): read with the same edges
// as the LF file, in every CSV dialect, compressed too; errors keep their line numbers.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>

#include "capture/capture_writer.h"
#include "capture/compression.h"
#include "capture/scope_csv_writer.h"
#include "capture_util.h"
#include "core/waveform.h"
#include "random_traffic.h"

namespace busdecode::test {
namespace {

Waveform crTraffic() {
    return randomTraffic(Timebase::fromSampleRate(10'000'000), 11, 3000, 50, 20, 5);
}

std::string readAll(const std::string& path) {
    std::ifstream f(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(f), {}};
}

// The file's LF and CR LF line ends, each made one CR.
std::string withCrLineEnds(std::string text) {
    std::string out;
    for (std::size_t i = 0; i < text.size(); ++i) {
        if (text[i] == '\r' && i + 1 < text.size() && text[i + 1] == '\n') continue;
        out += text[i] == '\n' ? '\r' : text[i];
    }
    return out;
}

void expectSameEdges(const std::string& lf_path, const std::vector<std::string>& names) {
    const std::string cr_path =
        tempCapture("cr-" + std::to_string(std::hash<std::string>{}(lf_path)),
                    withCrLineEnds(readAll(lf_path)));
    ASSERT_EQ(readAll(cr_path).find('\n'), std::string::npos);
    const Collected want = collectFile(lf_path, names);
    ASSERT_GT(want.edges.size(), 1000u);
    const Collected got = collectFile(cr_path, names);
    EXPECT_EQ(got.initial, want.initial);
    EXPECT_EQ(got.edges, want.edges);
    EXPECT_EQ(got.format, want.format + "+cr-lines");
    const std::string packed = cr_path + ".gz";
    compressFile(cr_path, packed, Compression::Gzip);
    EXPECT_EQ(collectFile(packed, names).edges, want.edges);
}

TEST(CrLineEnds, EveryCsvDialectReadsAsWithLf) {
    const Waveform w = crTraffic();
    for (CsvDialect d : {CsvDialect::SigrokDense, CsvDialect::SaleaeLogic2}) {
        const std::string lf = tempDir() + "/d" + std::to_string(int(d)) + ".csv";
        writeCsv(w, lf, d);
        SCOPED_TRACE(lf);
        expectSameEdges(lf, {"clk", "data"});
    }
}

TEST(CrLineEnds, ScopeCsvReadsAsWithLf) {
    const Waveform w = crTraffic();
    for (ScopeDialect d : {ScopeDialect::Rigol, ScopeDialect::Tektronix}) {
        const std::string lf = tempDir() + "/" + scopeDialectName(d) + ".csv";
        writeScopeCsv(w, lf, d, AnalogStyle{});
        SCOPED_TRACE(lf);
        expectSameEdges(lf, {});
    }
}

TEST(CrLineEnds, DetectedOnlyWhenTheFirstLineEndIsABareCr) {
    EXPECT_TRUE(hasBareCrLineEnds("Time [s],a\r0,1\r"));
    EXPECT_FALSE(hasBareCrLineEnds("Time [s],a\r\n0,1\r\n"));
    EXPECT_FALSE(hasBareCrLineEnds("Time [s],a\n0,1\r2,0\r"));
    EXPECT_FALSE(hasBareCrLineEnds("Time [s],a"));
    EXPECT_FALSE(hasBareCrLineEnds("Time [s],a\r"));  // one line: nothing to tell by
}

TEST(CrLineEnds, ErrorsNameTheLineByItsNumber) {
    const std::string path =
        tempCapture("bad-cr.csv", "Time [s],a,b\r0,0,1\r\r1e-6,1,1\r2e-6,x,0\r3e-6,0,0\r");
    const std::string msg = errorOf(path);
    EXPECT_EQ(msg.rfind(path + ":5: ", 0), 0u) << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
}

}  // namespace
}  // namespace busdecode::test
