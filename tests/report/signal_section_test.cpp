// The reports' signal section from the capture layer's events: a live run's gaps of
// dropped samples and a sequence capture's dead times are listed with their times, and a
// logic capture that has only those counts no pair faults.
#include <gtest/gtest.h>

#include "capture/capture_events.h"
#include "report/signal_section.h"

namespace busdecode {
namespace {

TEST(SignalSection, LiveGapsAreListedWithTheirTimesAndCount) {
    SignalSection s;
    const Timebase us{1, 1'000'000};
    EXPECT_TRUE(s.empty());
    EXPECT_TRUE(s.add(samplesDroppedEvent(1000, 1500, 500), us));
    EXPECT_TRUE(s.add(samplesDroppedEvent(4000, 4100, 100), us));
    EXPECT_FALSE(s.empty());
    const std::string text = s.text();
    EXPECT_NE(
        text.find(
            "  Samples dropped (live run, decoding fell behind): 600 in 2 gaps\n"
            "    1.000 ms to 1.500 ms: 500 samples dropped: decoding fell behind the device\n"),
        std::string::npos)
        << text;
    EXPECT_EQ(text.find("pair faults"), std::string::npos) << text;
    EXPECT_EQ(text.find("analog lines"), std::string::npos) << text;
    const std::string html = s.html();
    EXPECT_NE(html.find("<p>Samples dropped (live run, decoding fell behind): 600 in 2 gaps</p>"),
              std::string::npos)
        << html;
    EXPECT_NE(html.find("<li>4.000 ms to 4.100 ms: 100 samples dropped"), std::string::npos)
        << html;
    EXPECT_EQ(html.find("Pair faults"), std::string::npos) << html;
}

TEST(SignalSection, SegmentGapsAreListedWithTheirTimes) {
    SignalSection s;
    const Timebase ns{1, 1'000'000'000};
    EXPECT_TRUE(s.add(segmentGapEvent(24'950, 1'000'000'000, 2), ns));
    const std::string text = s.text();
    EXPECT_NE(
        text.find("  Not recorded (dead time between segments): 1 gaps\n"
                  "    24.950 us to 1.000000 s: not recorded: the dead time before segment 2\n"),
        std::string::npos)
        << text;
    EXPECT_NE(s.html().find("<li>24.950 us to 1.000000 s: not recorded"), std::string::npos)
        << s.html();
}

}  // namespace
}  // namespace busdecode
