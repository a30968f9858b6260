// SSI from a scope: generated frames written as each scope CSV dialect at 20 and 26 dB
// SNR, with edges of 20 % of a bit, ringing and an offset, decode every frame right, and
// the cable delay (median over the frames) within 1 % of the generator's.
#include <gtest/gtest.h>

#include <algorithm>

#include <fmt/format.h>

#include "capture/capture_reader.h"
#include "capture/scope_csv_writer.h"
#include "core/session.h"
#include "ssi_test_util.h"
#include "support/decode_events.h"
#include "support/paths.h"

namespace busdecode {
namespace {

TEST(SsiScope, EveryDialectDecodesEveryFrameWithItsCableDelay) {
    SsiGenConfig cfg;
    cfg.clock_hz = 1e6;
    cfg.delay_ns = 300;
    cfg.tail_ns = 30000;
    std::vector<SsiGenFrame> frames;
    for (std::uint64_t i = 0; i < 8; ++i) {
        SsiGenFrame f;
        f.word = (i * 0x2F1E3D5ull + 0x1234567ull) & ((1u << 25) - 1);
        f.pause_ns = 25000;
        frames.push_back(f);
    }
    const SsiGenerated g = generateSsi(cfg, frames);
    ssitest::registerSsi();
    for (const ScopeDialect d : kScopeDialects) {
        for (const double snr : {20.0, 26.0}) {
            SCOPED_TRACE(fmt::format("{} at {} dB", scopeDialectName(d), snr));
            AnalogStyle s;
            s.sample_ns = 10;
            s.low_v = 0;
            s.high_v = 5;
            s.offset_v = -0.3;
            s.rise_ns = 200;
            s.snr_db = snr;
            s.ringing = 0.15;
            s.ring_ns = 40;
            s.seed = std::uint64_t(d) * 100 + std::uint64_t(snr) + 7;
            const std::string p =
                test::tempDir() + fmt::format("/ssi_{}_{}.csv", scopeDialectName(d), snr);
            writeScopeCsv(g.wave, p, d, s);
            const auto decoded = test::eventsOfType(
                test::decodeEvents(p, {{"ssi",
                                        {{"clk", "clk"}, {"data", "data"}},
                                        {{"bits", "25"}, {"delay_ns", "auto"}}}}),
                "frame");
            ASSERT_EQ(decoded.size(), g.frames.size());
            std::vector<double> delays;
            for (std::size_t i = 0; i < decoded.size(); ++i) {
                const Event& e = decoded[i];
                SCOPED_TRACE(fmt::format("frame {}: {}", i, e.summary));
                EXPECT_TRUE(e.errors.empty());
                EXPECT_EQ(ssitest::u64(e, "raw"), g.frames[i].raw);
                delays.push_back(asDouble(*e.get("delay_ns")));
                // One edge each: a 300 ns delay is measured through 20 dB of noise.
                EXPECT_NEAR(delays.back(), cfg.delay_ns, cfg.delay_ns * 0.03);
            }
            std::nth_element(delays.begin(), delays.begin() + 4, delays.end());
            EXPECT_NEAR(delays[4], cfg.delay_ns, cfg.delay_ns / 100);
        }
    }
}

}  // namespace
}  // namespace busdecode
