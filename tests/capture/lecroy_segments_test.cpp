// LeCroy sequence-mode CSVs (several segments, each timed from its own trigger): every
// segment is read in time order, shifted to its trigger's time; a file whose segment
// lines do not match its count, or with more rows than its segments hold, is refused in
// one line naming file and line.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include "capture_util.h"

namespace busdecode::test {
namespace {

// `segments` segments of 40 samples 10 ns apart, each a pulse from sample 10 to 30, the
// k-th triggered k ms after the first; `listed` of them have their '#k' line.
std::string lecroy(int segments, int listed, int extra_rows = 0) {
    std::string s = fmt::format(
        "LECROYWR204M,51184,Waveform\nSegments,{},SegmentSize,40\n"
        "Segment,TrigTime,TimeSinceSegment1\n",
        segments);
    for (int k = 0; k < listed; ++k)
        s += fmt::format("#{},22-Jan-2015 11:35:11,{}   \n", k + 1, k * 1e-3);
    s += "Time,Ampl\n";
    for (int k = 0; k < segments; ++k)
        for (int i = 0; i < 40 + (k == segments - 1 ? extra_rows : 0); ++i)
            s += fmt::format("{:e},{}\n", -200e-9 + i * 10e-9, i >= 10 && i < 30 ? 3.3 : 0.0);
    return s;
}

TEST(LecroySegments, EverySegmentIsReadAtItsTriggerTime) {
    const Collected c = collectFile(tempCapture("seg3.csv", lecroy(3, 3)), {"Ampl"});
    EXPECT_EQ(c.format, "lecroy-csv");
    ASSERT_EQ(c.edges.size(), 6u);
    for (int k = 0; k < 3; ++k) {
        // The crossing halfway between samples 9 and 10 (and 29 and 30) of segment k.
        const double rise = k * 1e6 - 200 + 95, fall = k * 1e6 - 200 + 295;
        EXPECT_NEAR(c.tb.toNsF(double(c.edges[2 * k].t)), rise, 1) << k;
        EXPECT_EQ(c.edges[2 * k].level, 1u);
        EXPECT_NEAR(c.tb.toNsF(double(c.edges[2 * k + 1].t)), fall, 1) << k;
        EXPECT_EQ(c.edges[2 * k + 1].level, 0u);
    }
}

TEST(LecroySegments, SegmentLinesThatDoNotMatchTheCountAreRefused) {
    const std::string p = tempCapture("seg_missing.csv", lecroy(3, 2));
    EXPECT_EQ(errorOf(p), p + ":6: LeCroy file of 3 segments lists 2 segment lines before 'Time,'");
}

TEST(LecroySegments, MoreRowsThanTheSegmentsHoldAreRefused) {
    const std::string p = tempCapture("seg_long.csv", lecroy(2, 2, 1));
    EXPECT_NE(errorOf(p).find(p + ":87: more rows than 2 segments of 40"), std::string::npos)
        << errorOf(p);
}

}  // namespace
}  // namespace busdecode::test
