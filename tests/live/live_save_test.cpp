// --save's session: nothing is written when no sample came (a run stopped before its first
// packet), and lines that were not acquired get no name of their own in the metadata.
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <vector>

#include "capture/capture_reader.h"
#include "capture/live_save.h"
#include "support/paths.h"

namespace busdecode::test {
namespace {

TEST(LiveSave, NoSampleWritesNothing) {
    const std::string path = tempDir() + "/nothing.sr";
    LiveSaver saver(path, {"D0", "", "D2"}, 1'000'000);
    EXPECT_FALSE(saver.finish());
    EXPECT_FALSE(std::filesystem::exists(path));
}

TEST(LiveSave, LinesNotAcquiredAreNotNamed) {
    const std::string path = tempDir() + "/saved.sr";
    LiveSaver saver(path, {"D0", "", "CLK"}, 1'000'000);
    const std::vector<std::uint8_t> samples{0, 5, 0, 5};
    saver.add(samples.data(), samples.size(), 1);
    ASSERT_TRUE(saver.finish());
    const auto reader = openCapture(path, OpenOptions{});
    ASSERT_EQ(reader->signals().size(), 3u);
    EXPECT_EQ(reader->signals()[0].name, "D0");
    EXPECT_EQ(reader->signals()[1].name, "D1");  // sigrok's name for a probe without one
    EXPECT_EQ(reader->signals()[2].name, "CLK");
}

}  // namespace
}  // namespace busdecode::test
