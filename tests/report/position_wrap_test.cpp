// Positions that wrap: 16-bit SSI and 26-bit BiSS-C encoders generated crossing zero in
// both directions pass `max_position_jump` with a small limit (the rollover is a step of
// a few counts, not of 2^n); a real jump still fails, with the time of its frame.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "bissc_decoder.h"
#include "bissc_generator.h"
#include "capture/capture_reader.h"
#include "core/registry.h"
#include "core/session.h"
#include "report/capture_stats.h"
#include "report/position_wrap.h"
#include "ssi_generator.h"
#include "ssi_info.h"
#include "verify/rule_checker.h"
#include "verify/rules.h"

namespace busdecode {
namespace {

class StatsSink : public OutputSink {
public:
    void begin(const CaptureFacts& f) override { stats.begin(f); }
    void onEvent(const Event& e, const CaptureFacts&) override { stats.add(e); }
    void end(const CaptureFacts& f) override { stats.end(f); }
    CaptureStats stats;
};

struct Checked {
    RuleOutcome jump;
    PositionStats position;
};

Checked verify(const Waveform& w, const DecoderRequest& request, const std::string& rules_text) {
    Registry::instance().add(makeSsiFactory());
    Registry::instance().add(makeBisscFactory());
    auto reader = memoryReader(w);
    Session session({request}, *reader, "wrap.vcd");
    RuleChecker checker(parseRules(rules_text, "r.toml", {}));
    StatsSink stats;
    session.addSink(&checker);
    session.addSink(&stats);
    session.run();
    for (const auto& o : checker.outcomes())
        if (o.rule == "max_position_jump") return {o, *stats.stats.position(request.proto)};
    throw std::runtime_error("no max_position_jump outcome");
}

// Counts 65530, 65533, 0 (65536), 3, ... then back down across zero.
std::vector<std::uint64_t> acrossZero(std::uint64_t modulus, int step, int jump_at = -1) {
    std::vector<std::uint64_t> out;
    std::int64_t p = -9;
    for (int i = 0; i < 12; ++i) {
        p += i < 6 ? step : -step;
        if (i == jump_at) p += 5000;
        out.push_back(std::uint64_t((p % std::int64_t(modulus) + std::int64_t(modulus)) %
                                    std::int64_t(modulus)));
    }
    return out;
}

SsiGenerated ssiEncoder(const std::vector<std::uint64_t>& positions) {
    SsiGenConfig cfg;
    cfg.data_bits = 16;
    std::vector<SsiGenFrame> frames;
    for (auto p : positions) {
        SsiGenFrame f;
        f.word = p;
        frames.push_back(f);
    }
    return generateSsi(cfg, frames);
}

DecoderRequest ssiRequest() {
    return {"ssi", {}, {{"bits", "16"}, {"st_bits", "16"}}};
}

TEST(PositionWrap, ShortestDifferenceFoldsIntoHalfTheModulus) {
    EXPECT_EQ(shortestDifference(65530, 3, 65536), 9);
    EXPECT_EQ(shortestDifference(3, 65530, 65536), -9);
    EXPECT_EQ(shortestDifference(100, 40000, 65536), -25636);
    EXPECT_EQ(shortestDifference(65530, 3, 0), 3 - 65530);  // not modular
}

TEST(PositionWrap, SsiSixteenBitsAcrossZeroBothWaysPassesASmallLimit) {
    const auto g = ssiEncoder(acrossZero(65536, 3));
    const Checked c = verify(g.wave, ssiRequest(), "[ssi]\nmax_position_jump = 4\n");
    EXPECT_TRUE(c.jump.passed) << c.jump.message;
    EXPECT_EQ(c.jump.message, "0 jumps (limit 4, largest 3)");
    EXPECT_EQ(c.position.max_jump, 3);
    EXPECT_EQ(c.position.modulus, 65536);
}

TEST(PositionWrap, SsiRealJumpStillFailsWithItsTime) {
    const auto g = ssiEncoder(acrossZero(65536, 3, 8));
    const Checked c = verify(g.wave, ssiRequest(), "[ssi]\nmax_position_jump = 4\n");
    EXPECT_FALSE(c.jump.passed);
    EXPECT_EQ(c.jump.offending, 1u);  // the encoder moved on from where it jumped to
    ASSERT_TRUE(c.jump.first_ns);
    EXPECT_DOUBLE_EQ(*c.jump.first_ns, g.wave.timebase.toNsF(double(g.frames[8].start)));
    EXPECT_NE(c.jump.message.find("jump 4997"), std::string::npos) << c.jump.message;
}

TEST(PositionWrap, ModulusOptionOverridesTheLayout) {
    // A layout the checker cannot know: the user says positions do not wrap.
    const auto g = ssiEncoder(acrossZero(65536, 3));
    const Checked c =
        verify(g.wave, ssiRequest(), "[ssi]\nmax_position_jump = 4\nposition_modulus = 0\n");
    EXPECT_FALSE(c.jump.passed) << c.jump.message;
}

Waveform bisscEncoder(const std::vector<std::uint64_t>& positions, BisscGenerator* out = nullptr) {
    BisscGenConfig cfg;
    cfg.bits = 26;
    BisscGenerator gen(cfg);
    for (auto p : positions) {
        BisscFrameSpec f;
        f.data = p;
        gen.addFrame(f);
    }
    if (out) *out = gen;
    return gen.build();
}

TEST(PositionWrap, BisscTwentySixBitsAcrossZeroBothWaysPassesASmallLimit) {
    const std::uint64_t m = std::uint64_t(1) << 26;
    const Checked c = verify(bisscEncoder(acrossZero(m, 5)), {"bissc", {}, {}},
                             "[bissc]\nmax_position_jump = 8\n");
    EXPECT_TRUE(c.jump.passed) << c.jump.message;
    EXPECT_EQ(c.position.max_jump, 5);
    EXPECT_EQ(c.position.modulus, double(m));
    // Drawn unwrapped: the trace goes below zero and back instead of leaping to 2^26.
    double lo = 1e300, hi = -1e300;
    for (const auto& p : c.position.trace.points()) {
        lo = std::min(lo, p.lo);
        hi = std::max(hi, p.hi);
    }
    EXPECT_LT(hi - lo, 40);
}

TEST(PositionWrap, BisscRealJumpStillFailsWithItsTime) {
    const std::uint64_t m = std::uint64_t(1) << 26;
    BisscGenerator gen{BisscGenConfig{}};
    const Waveform w = bisscEncoder(acrossZero(m, 5, 3), &gen);
    const Checked c = verify(w, {"bissc", {}, {}}, "[bissc]\nmax_position_jump = 8\n");
    EXPECT_FALSE(c.jump.passed);
    ASSERT_TRUE(c.jump.first_ns);
    EXPECT_DOUBLE_EQ(*c.jump.first_ns, w.timebase.toNsF(double(gen.frames()[3].start)));
    EXPECT_NE(c.jump.message.find("jump 5005"), std::string::npos) << c.jump.message;
}

}  // namespace
}  // namespace busdecode
