// The example captures in captures/spi_* are what the generator makes: read back from the
// committed files (VCD and Saleae CSV), they decode to the generated words.
#include <gtest/gtest.h>

#include <filesystem>

#include "core/registry.h"
#include "core/session.h"
#include "spi_examples.h"
#include "spi_info.h"
#include "support/decode_events.h"
#include "support/paths.h"

using namespace busdecode;
using namespace busdecode::test;

namespace {
std::string describe(const Event& e) {
    std::string s =
        e.type + " " + std::to_string(e.start) + "-" + std::to_string(e.end) + " " + e.summary;
    for (const auto& x : e.errors)
        s += " !" + x;
    return s;
}
}  // namespace

TEST(SpiExamples, CommittedCapturesDecodeLikeTheTruth) {
    Registry::instance().add(makeSpiFactory());
    for (const auto& ex : spiExamples()) {
        SCOPED_TRACE(ex.file);
        const std::string path = examplePath(ex.file);
        ASSERT_TRUE(std::filesystem::exists(path)) << "run make_examples captures spi";
        auto truth = decodeWaveform(ex.wave, ex.requests);
        const auto events = decodeEvents(path, ex.requests);
        ASSERT_EQ(events.size(), truth.size());
        ASSERT_GE(truth.size(), 6u);
        for (std::size_t i = 0; i < truth.size(); ++i) {
            // Saleae CSV times are seconds with limited digits: allow a tick of rounding.
            EXPECT_EQ(events[i].summary, truth[i].summary);
            EXPECT_EQ(events[i].errors, truth[i].errors);
            EXPECT_NEAR(double(events[i].start), double(truth[i].start), 1.0)
                << describe(events[i]);
        }
    }
}

TEST(SpiExamples, Mode0Lsb16Truth) {
    Registry::instance().add(makeSpiFactory());
    const auto ex = spiExamples().at(0);
    auto ev = decodeWaveform(ex.wave, ex.requests);
    std::vector<std::string> got;
    for (const auto& e : ev)
        got.push_back(e.summary + (e.errors.empty() ? "" : " !" + e.errors[0]));
    const std::vector<std::string> want = {"MOSI 0x1234 MISO 0xFFFF",
                                           "MOSI 0xABCD MISO 0x0001",
                                           "MOSI 0x8001 MISO 0x7FFE",
                                           "MOSI 0x0F0F MISO 0xF0F0",
                                           "MOSI 0x555 MISO 0x2AA (11 of 16 bits) !short_frame",
                                           "MOSI 0xC3C3 MISO 0x3C3C"};
    EXPECT_EQ(got, want);
}
