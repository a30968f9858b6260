// Scope CSVs and sigrok analog sessions: every dialect read from real files (committed
// under tests/data/real/formats) and from layouts written here, the analog CSV against
// its own .sr, the logic byte columns, and broken files.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "capture_util.h"

namespace busdecode::test {
namespace {

std::string real(const std::string& rel) {
    return sourceDir() + "/tests/data/real/formats/" + rel;
}

std::vector<std::string> names(const Collected& c) {
    std::vector<std::string> out;
    for (const auto& s : c.signals)
        out.push_back(s.name);
    return out;
}

// Edges of one line, in ns from the capture start.
std::vector<double> lineNs(const Collected& c, std::uint32_t line) {
    std::vector<double> out;
    for (const auto& e : c.edges)
        if (e.line == line) out.push_back(c.tb.toNsF(double(e.t - c.start)));
    return out;
}

struct RealFile {
    const char* path;
    const char* format;
    std::vector<std::string> signals;
    std::size_t min_edges;  // on the first signal
};

TEST(ScopeCsv, EveryRealDialectIsReadWithItsChannelsAndEdges) {
    const std::vector<RealFile> files = {
        {"rigol/DS1054Z-A.csv", "rigol-csv", {"CH1", "CH2", "CH3", "CH4"}, 2},
        {"rigol/DS1074Z-B.csv", "rigol-csv", {"CH1", "CH2", "CH3"}, 2},
        {"rigol/DS2072A-1.csv", "rigol-csv", {"CH1", "CH2"}, 2},
        {"rigol/DS4024-A.csv", "rigol-csv", {"CH1", "CH2"}, 2},
        {"rigol/DS1102E-D.csv", "rigol-csv", {"CH1", "CH2"}, 2},
        {"rigol/DS1102D-A.csv", "rigol-csv", {"CH1", "CH2"}, 2},
        {"rigol/DS1204B-F.csv", "rigol-csv", {"CH2", "CH4"}, 2},
        {"rigol/DS1052E.csv", "rigol-csv", {"CH1", "CH2"}, 2},
        {"mixed-gpl/rigol_ds1000e.csv", "rigol-csv", {"CH2"}, 2},
        {"keysight/scope_3.csv", "keysight-csv", {"CH1", "CH2"}, 2},
        {"keysight/scope_7_1.csv", "keysight-csv", {"CH1"}, 2},
        {"keysight/scope_7_2.csv", "keysight-csv", {"CH2"}, 2},
        {"tek-mdo/RTC.csv", "tektronix-csv", {"CH1", "CH2"}, 20},
        {"tek-mdo/RTC.sr", "sigrok-sr", {"SDA", "SCL"}, 20},
        {"mixed-gpl/picoscope6_excerpt.csv", "picoscope-csv", {"A", "B"}, 0},
    };
    for (const auto& f : files) {
        SCOPED_TRACE(f.path);
        const Collected c = collectFile(real(f.path));
        EXPECT_EQ(c.format, f.format);
        EXPECT_EQ(names(c), f.signals);
        EXPECT_GE(lineNs(c, 0).size(), f.min_edges);
        EXPECT_LT(c.start, c.end);
    }
}

TEST(ScopeCsv, TimeComesFromTheFilesOwnTimeBase) {
    // DS4024's index column starts at 22: t = Start + 22 * Increment.
    Collected c = collectFile(real("rigol/DS4024-A.csv"), {"CH1"});
    EXPECT_NEAR(c.tb.toNsF(double(c.start)), (-1.4e-3 + 22 * 2e-6) * 1e9, 1e-3);
    // PicoScope's "(ms)" scales its time column.
    c = collectFile(real("mixed-gpl/picoscope6_excerpt.csv"), {"A"});
    EXPECT_NEAR(c.tb.toNsF(double(c.start)), -5008, 1e-3);
    EXPECT_NEAR(c.tb.toNsF(double(c.end)), 12520, 1e-3);
}

TEST(ScopeCsv, TektronixCsvGivesTheEdgesOfItsOwnSrWithinTwoSamples) {
    const Collected csv = collectFile(real("tek-mdo/RTC.csv"), {"CH1", "CH2"});
    const Collected sr = collectFile(real("tek-mdo/RTC.sr"), {"SDA", "SCL"});
    for (std::uint32_t line = 0; line < 2; ++line) {
        const auto a = lineNs(csv, line), b = lineNs(sr, line);
        ASSERT_EQ(a.size(), b.size()) << "line " << line;
        ASSERT_GT(a.size(), 20u);
        for (std::size_t i = 0; i < a.size(); ++i)
            EXPECT_NEAR(a[i], b[i], 2 * 20.0) << "edge " << i;  // 50 MS/s: 20 ns a sample
    }
}

TEST(ScopeCsv, RigolLogicColumnsD0AndD12ToggleAt1kHz) {
    const Collected c =
        collectFile(real("mixed-gpl/rigol_ds1000z_mixed_signal.csv"), {"D0", "D12", "D5"});
    EXPECT_TRUE(lineNs(c, 2).empty());
    for (std::uint32_t line = 0; line < 2; ++line) {
        const auto t = lineNs(c, line);
        ASSERT_GE(t.size(), 4u) << line;
        // 1 ms a period; the file's duty cycle is 252/248 samples of 2 us.
        for (std::size_t i = 2; i < t.size(); ++i)
            EXPECT_NEAR(t[i] - t[i - 2], 1'000'000, 1) << "line " << line << " edge " << i;
        for (std::size_t i = 1; i < t.size(); ++i)
            EXPECT_NEAR(t[i] - t[i - 1], 500'000, 4'001) << "line " << line << " edge " << i;
    }
}

TEST(ScopeCsv, EachBitOfAByteColumnHasItsOwnNameAndTheTitleNamesNone) {
    const auto r = openCapture(real("mixed-gpl/rigol_ds1000z_mixed_signal.csv"), {});
    std::vector<std::string> full;
    for (const auto& s : r->signals())
        full.push_back(s.full_name);
    EXPECT_NE(std::find(full.begin(), full.end(), "D12"), full.end());
    EXPECT_EQ(std::find(full.begin(), full.end(), "D15-D8"), full.end());
    const auto run = runDecode(
        {real("mixed-gpl/rigol_ds1000z_mixed_signal.csv"), "--proto", "uart", "--map", "rx=D7-D0"});
    EXPECT_EQ(run.status, 2);
    EXPECT_NE(run.err.find("no such signal"), std::string::npos) << run.err;
}

TEST(ScopeCsv, EdgesAreTimedAtTheThresholdCrossingBetweenSamples) {
    // A 1 V/us ramp sampled every 1 us, crossing 1.5 V at 1.5 us, and falling back.
    const std::string p = tempCapture("ramp.csv",
                                      "x-axis,1\nsecond,Volt\n0,0\n1e-6,1\n2e-6,2\n3e-6,3\n"
                                      "4e-6,3\n5e-6,2.5\n6e-6,0.5\n7e-6,0\n8e-6,0\n");
    const Collected c = collectFile(p);
    ASSERT_EQ(c.edges.size(), 2u);
    EXPECT_NEAR(c.tb.toNsF(double(c.edges[0].t)), 1500, 1);
    EXPECT_EQ(c.edges[0].level, 1u);
    EXPECT_NEAR(c.tb.toNsF(double(c.edges[1].t)), 5500, 1);
}

TEST(ScopeCsv, GivenThresholdAndHysteresisApply) {
    const std::string p = tempCapture("steps.csv",
                                      "x-axis,1\nsecond,Volt\n0,0\n1e-6,1\n2e-6,2\n3e-6,3\n"
                                      "4e-6,3\n5e-6,0\n6e-6,0\n7e-6,3\n8e-6,0\n");
    OpenOptions o;
    o.thresholds = {{"CH1", 0.5}};
    o.hysteresis = 0;
    Collected c = collectFile(p, {}, o);
    ASSERT_FALSE(c.edges.empty());
    EXPECT_NEAR(c.tb.toNsF(double(c.edges[0].t)), 500, 1);
    o.thresholds = {{"", 2.5}};
    c = collectFile(p, {}, o);
    ASSERT_FALSE(c.edges.empty());
    EXPECT_NEAR(c.tb.toNsF(double(c.edges[0].t)), 2500, 1);
    o.thresholds = {{"CH9", 1}};
    EXPECT_NE(errorOf(p, o).find("has no signal 'CH9'"), std::string::npos) << errorOf(p, o);
}

TEST(ScopeCsv, LayoutsWithoutARealFileAreRead) {
    struct Case {
        const char* name;
        const char* text;
        const char* format;
        const char* signal;
    };
    const std::vector<Case> cases = {
        {"tds.csv",
         "Record Length,6,,  -0.000002000000,   0.00000,\n"
         "Sample Interval,1.000000e-06,,  -0.000001000000,   0.00000,\n"
         "Trigger Point,2,,  00.000000000000,   3.30000,\n"
         "Source,CH1,,  00.000001000000,   3.30000,\n"
         ",,,  00.000002000000,   0.00000,\n"
         ",,,  00.000003000000,   0.00000,\n",
         "tektronix-csv", "CH1"},
        {"siglent.csv",
         "Record Length,Analog:4\nSample Interval,CH1:0.000001\nSource,CH1\nSecond,Volt\n"
         " 0.00000000000,0.00\n 0.00000100000,3.30\n 0.00000200000,3.30\n 0.0000030,0.00\n",
         "siglent-csv", "CH1"},
        {"lecroy.csv",
         "LECROYWR204M,51184,Waveform\nSegments,1,SegmentSize,4\n"
         "Segment,TrigTime,TimeSinceSegment1\n#1,22-Jan-2015 11:35:11,0   \nTime,Ampl\n"
         "-2e-6,0\n-1e-6,3.3\n0,3.3\n1e-6,0\n",
         "lecroy-csv", "Ampl"},
        {"pico_en.csv", "Time,Channel A\n(us),(V)\n\n0,0\n1,5\n2,5\n3,0\n", "picoscope-csv", "A"},
        // A German PicoScope: its words, semicolons and decimal commas.
        {"pico_de.csv",
         "Zeit;Kanal B\r\n(ms);(V)\r\n\r\n0,000;0,01\r\n0,001;4,98\r\n0,002;5,0\r\n"
         "0,003;0,02\r\n",
         "picoscope-csv", "B"},
    };
    for (const auto& k : cases) {
        SCOPED_TRACE(k.name);
        const Collected c = collectFile(tempCapture(k.name, k.text));
        EXPECT_EQ(c.format, k.format);
        ASSERT_FALSE(c.signals.empty());
        EXPECT_EQ(c.signals[0].name, k.signal);
        ASSERT_EQ(c.edges.size(), 2u);
        EXPECT_EQ(c.edges[0].level, 1u);
        // High for two samples of 1 us in every file: the crossings 2 us apart.
        EXPECT_NEAR(c.tb.toNsF(double(c.edges[1].t - c.edges[0].t)), 2000, 1);
    }
}

TEST(ScopeCsv, BrokenFilesNameFileAndLine) {
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"X,CH1,Start,Increment,\nSequence,Volt,0,1e-6\n0,1.0,\n1,2.0,3.0,4.0\n",
         "ragged.csv:4: expected 2 fields, found 4"},
        {"x-axis,1\nsecond,Volt\n0,1.0\n1e-6,abc\n", "nonnumber.csv:4: expected a number"},
        {"X,CH1,Start,Increment,\n0,1.0,\n", "nounits.csv:2: expected Rigol's units row"},
        {"x-axis,1,2\n0,1,2\n", "nounits2.csv:2: expected the units row"},
        {"Time;Channel A\n0;1\n", "nounits3.csv:2: expected PicoScope's units row"},
        {"x-axis,1\nsecond,Volt\n1e-6,1.0\n0,2.0\n", "backwards.csv:4: time going backwards"},
    };
    const char* files[] = {"ragged.csv",   "nonnumber.csv", "nounits.csv",
                           "nounits2.csv", "nounits3.csv",  "backwards.csv"};
    for (std::size_t i = 0; i < cases.size(); ++i) {
        const std::string p = tempCapture(files[i], cases[i].first);
        const std::string err = errorOf(p);
        EXPECT_NE(err.find(cases[i].second), std::string::npos) << err;
        EXPECT_EQ(err.find('\n'), std::string::npos) << err;
    }
    const auto r = runDecode({tempDir() + "/ragged.csv", "--proto", "uart", "--map", "rx=CH1"});
    EXPECT_EQ(r.status, 2);
    EXPECT_NE(r.err.find("ragged.csv:4:"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace busdecode::test
