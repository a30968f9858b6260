// Row-per-sample captures without a stated rate: Vivado ILA CSV exports and headerless
// sample lists (ChipScope .prn, spaces, commas; CRLF or LF). Round trips from generated
// traffic against its VCD, vector bits as name[3], and bad rows naming dialect and line.
#include <gtest/gtest.h>

#include "capture/capture_writer.h"
#include "capture_util.h"
#include "core/waveform.h"
#include "random_traffic.h"

namespace busdecode::test {
namespace {

Waveform denseTraffic() {
    return randomTraffic(Timebase::fromSampleRate(1'000'000), 9, 3000, 5, 0, 3);
}

OpenOptions rate(double hz) {
    OpenOptions o;
    o.rate_hz = hz;
    return o;
}

TEST(SampleRows, IlaCsvRoundTripByNameAndByBit) {
    const Waveform w = denseTraffic();
    const std::string p = tempDir() + "/ila.csv", vcd = tempDir() + "/ila.vcd";
    writeSampleRows(w, p, SampleRowsDialect::VivadoIlaCsv);
    writeVcd(w, vcd);
    const Collected want = collectFile(vcd, {"clk", "data", "cs"});
    const Collected byName = collectFile(p, {"clk", "data", "cs"}, rate(1e6));
    EXPECT_EQ(byName.format, "vivado-ila-csv");
    ASSERT_EQ(byName.signals.size(), 4u);  // three probes and the packed one, no counters
    EXPECT_EQ(byName.signals[3].full_name, "top/u_ila/lines");
    EXPECT_EQ(byName.signals[3].width, 3);
    EXPECT_EQ(byName.initial, want.initial);
    EXPECT_EQ(inNs(byName), inNs(want));
    const Collected byBit = collectFile(p, {"lines[0]", "lines[1]", "lines[2]"}, rate(1e6));
    EXPECT_EQ(inNs(byBit), inNs(want));
}

TEST(SampleRows, IlaCsvWideHexProbe) {
    const std::string p =
        tempCapture("wide.csv",
                    "Sample in Buffer,Sample in Window,TRIGGER,u/RAW_VALUE[127:0]\r\n"
                    "Radix - UNSIGNED,UNSIGNED,UNSIGNED,HEX\r\n"
                    "0,0,1,00000000000000000000000000000000\r\n"
                    "1,1,0,80000000000000000000000000000001\r\n"
                    "2,2,0,00000000000000000000000000000001\r\n");
    const Collected c =
        collectFile(p, {"RAW_VALUE[127]", "RAW_VALUE[0]", "RAW_VALUE[64]"}, rate(100e6));
    EXPECT_EQ(c.edges, (std::vector<Edge>{Edge(1, 0, 1), Edge(1, 1, 1), Edge(2, 0, 0)}));
    EXPECT_EQ(c.end, 2);
}

TEST(SampleRows, PrnRoundTripAndOtherSeparators) {
    const Waveform w = denseTraffic();
    const std::string p = tempDir() + "/list.prn", vcd = tempDir() + "/list.vcd";
    writeSampleRows(w, p, SampleRowsDialect::ChipScopePrn);
    writeVcd(w, vcd);
    const Collected want = collectFile(vcd, {"clk", "data", "cs"});
    const Collected got = collectFile(p, {"0", "1", "2"}, rate(1e6));
    EXPECT_EQ(got.format, "sample-list");
    EXPECT_EQ(got.initial, want.initial);
    EXPECT_EQ(inNs(got), inNs(want));
    // Spaces with LF, commas, a TAB run: the same three rows.
    for (const std::string text :
         {"1 0\n0 0\n0 1\n", "1,0\r\n0,0\r\n0,1\r\n", "1\t\t0\n0 ,0\n0\t1"}) {
        const Collected c = collectFile(tempCapture("l.txt", text), {}, rate(10));
        EXPECT_EQ(c.signals.size(), 2u) << text;
        EXPECT_EQ(c.initial, (std::vector<std::uint8_t>{1, 0})) << text;
        EXPECT_EQ(c.edges, (std::vector<Edge>{Edge(1, 0, 0), Edge(2, 1, 1)})) << text;
    }
}

TEST(SampleRows, ErrorsNameDialectAndLine) {
    std::string p = tempCapture("norate.prn", "1\t1\t\r\n0\t1\t\r\n");
    EXPECT_EQ(errorOf(p), p + ": a sample list has no time column or sample rate: give the "
                              "sample rate with --rate HZ");
    p = tempCapture("short.prn", "1\t1\n0\t1\n1\n");
    EXPECT_EQ(errorOf(p, rate(1)), p + ":3: sample list: a row of 1 fields, the first had 2");
    p = tempCapture("two.prn", "1 1\n0 2\n");
    EXPECT_EQ(errorOf(p, rate(1)), p + ":2: sample list: '2' is not 0 or 1 (binary)");
    const std::string head =
        "Sample in Buffer,Sample in Window,TRIGGER,a,b[3:0]\nRadix - UNSIGNED,UNSIGNED,UNSIGNED,";
    p = tempCapture("ila1.csv", head + "BINARY,HEX\n0,0,1,0,F\n1,1,0,0,X\n");
    EXPECT_EQ(errorOf(p, rate(1)), p + ":4: Vivado ILA CSV: 'X' is not a hex value");
    p = tempCapture("ila2.csv", head + "BINARY,SIGNED\n0,0,1,0,1\n");
    EXPECT_EQ(errorOf(p, rate(1)),
              p + ":2: Vivado ILA CSV: probe 'b[3:0]' is in radix 'SIGNED': export it as HEX, "
                  "BINARY or UNSIGNED");
    p = tempCapture("ila3.csv", head + "BINARY\n0,0,1,0,1\n");
    EXPECT_EQ(errorOf(p, rate(1)), p + ":2: Vivado ILA CSV: 4 radixes for 5 probes");
    p = tempCapture("ila4.csv", head + "BINARY,HEX\n0,0,1,0,1\n");
    EXPECT_EQ(errorOf(p), p + ": a Vivado ILA CSV has no time column or sample rate: give the "
                              "sample rate with --rate HZ");
}

}  // namespace
}  // namespace busdecode::test
