// Real clock + data traffic: the digital caliper captures of sigrok-dumps (24-bit words,
// LSB first, the caliper drives data while the clock is low and the reader samples on
// rising edges). Frames must sit where sigrok's own caliper decoder put its annotations
// (within one bit), and each word carries the value in the file name.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>

#include <fmt/format.h>

#include "capture/capture_reader.h"
#include "core/session.h"
#include "ssi_test_util.h"
#include "support/decode_events.h"
#include "support/paths.h"

using namespace busdecode;
using namespace busdecode::ssitest;

namespace {

const std::map<std::string, std::string> kCaliperOptions = {
    {"bits", "24"},   {"lsb_first", "1"},       {"sample_edge", "rising"}, {"lead", "1"},
    {"st_bits", "0"}, {"clock_min_hz", "1000"}, {"tm_min_us", "0"},        {"tm_max_us", "1000"},
};

std::string caliperDir() {
    return test::realCaptures() + "/sigrok-dumps/caliper";
}

std::vector<Event> decodeFile(const std::string& path) {
    registerSsi();
    DecoderRequest r;
    r.proto = "ssi";
    r.map = {{"clk", "CLK"}, {"data", "DATA"}};
    r.options = kCaliperOptions;
    return test::eventsOfType(test::decodeEvents(path, {r}), "frame");
}

// The word a caliper sends for the value in its file name: 20-bit magnitude in 1/100 mm
// or 1/2000 in, bit 20 the sign, bit 23 inches.
std::uint64_t expectedWord(const std::string& name) {
    static const std::regex re(R"(caliper(-?)([0-9.]+)(mm|in))");
    std::smatch m;
    if (!std::regex_search(name, m, re)) throw std::runtime_error("bad name " + name);
    const bool neg = m[1] == "-", inch = m[3] == "in";
    const double v = std::stod(m[2]);
    const auto mag = std::uint64_t(std::llround(v * (inch ? 2000 : 100)));
    return mag | (neg ? 1u << 20 : 0) | (inch ? 1u << 23 : 0);
}

struct Expected {
    std::int64_t start, end;
    bool timeout;
    int timeout_bits;
};

std::vector<Expected> readExpected(const std::string& path) {
    std::ifstream f(path);
    std::vector<Expected> out;
    std::string line;
    static const std::regex re(R"(^(\d+)-(\d+) caliper: (\w+): (.*)$)");
    static const std::regex bits_re(R"(with (\d+) bits)");
    while (std::getline(f, line)) {
        std::smatch m;
        if (!std::regex_match(line, m, re)) continue;
        Expected e{std::stoll(m[1]), std::stoll(m[2]), m[3] == "warning", 0};
        std::string rest = m[4];
        if (std::smatch b; e.timeout && std::regex_search(rest, b, bits_re))
            e.timeout_bits = std::stoi(b[1]);
        out.push_back(e);
    }
    return out;
}

}  // namespace

TEST(SsiCaliper, FramesWhereSigrokFindsMeasurements) {
    const std::string exp_dir = test::realCaptures() + "/sigrok-test/decoder/test/caliper";
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"caliper0.55mm.sr", "caliper_pos_mm.output"},
        {"caliper-123.45mm.sr", "caliper_neg_mm.output"},
        {"caliper0.5in.sr", "caliper_pos_in.output"},
    };
    for (const auto& [capture, output] : cases) {
        SCOPED_TRACE(capture);
        const auto frames = decodeFile(caliperDir() + "/" + capture);
        const auto expected = readExpected(exp_dir + "/" + output);
        ASSERT_GE(expected.size(), 13u);
        // sigrok says nothing about a burst cut by the end of the capture; we report it as a
        // short frame after the last of sigrok's.
        ASSERT_GE(frames.size(), expected.size());
        for (std::size_t i = expected.size(); i < frames.size(); ++i) {
            EXPECT_TRUE(frames[i].hasError("short_frame")) << describe(frames[i]);
            EXPECT_GT(frames[i].start, expected.back().end);
        }
        ASSERT_LE(frames.size(), expected.size() + 1);
        const std::uint64_t word = expectedWord(capture);
        for (std::size_t i = 0; i < expected.size(); ++i) {
            const Event& e = frames[i];
            const Expected& x = expected[i];
            SCOPED_TRACE(
                fmt::format("frame {}: {} expected {}-{}", i, describe(e), x.start, x.end));
            const double bit = 1e6 / asDouble(*e.get("clock_hz"));  // samples at 1 MHz
            EXPECT_LE(std::abs(double(e.start - x.start)), bit);
            if (x.timeout) {
                // sigrok ends its warning when its timeout fires; the burst ended earlier.
                EXPECT_LE(e.end, x.end);
                EXPECT_TRUE(e.hasError("short_frame"));
                EXPECT_EQ(i64(e, "bits"), x.timeout_bits);
                continue;
            }
            EXPECT_LE(std::abs(double(e.end - x.end)), bit);
            EXPECT_EQ(i64(e, "bits"), 24);
            EXPECT_EQ(u64(e, "raw"), word) << fmt::format("{:#x}", u64(e, "raw"));
            EXPECT_FALSE(e.hasError("short_frame"));
            EXPECT_FALSE(e.hasError("glitch"));
            EXPECT_FALSE(e.hasError("late_data"));
            EXPECT_FALSE(e.hasError("sample_late"));
            EXPECT_FALSE(e.hasError("clock_range"));
        }
    }
}

TEST(SsiCaliper, EveryCaptureCarriesItsFileNameValue) {
    int files = 0;
    for (const auto& entry : std::filesystem::directory_iterator(caliperDir())) {
        const std::string name = entry.path().filename().string();
        if (entry.path().extension() != ".sr") continue;
        SCOPED_TRACE(name);
        ++files;
        const auto frames = decodeFile(entry.path().string());
        const std::uint64_t word = expectedWord(name);
        int good = 0;
        for (const auto& e : frames) {
            if (e.hasError("short_frame") || e.hasError("glitch")) continue;
            EXPECT_EQ(u64(e, "raw"), word) << describe(e);
            EXPECT_EQ(i64(e, "bits"), 24);
            EXPECT_NEAR(asDouble(*e.get("clock_hz")), 5000, 1000);
            ++good;
        }
        // About one measurement every 72 ms in a 1 s capture.
        EXPECT_GE(good, 13) << name;
        EXPECT_LE(frames.size(), 15u) << name;
    }
    EXPECT_EQ(files, 14);
}
