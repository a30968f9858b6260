// BiSS-C from a scope: generated frames written as each scope CSV dialect at 20 and 26 dB
// SNR, with edges of 20 % of a bit, ringing and an offset, decode every frame right with
// a good CRC, and the line delay within 1 % of the generator's (the delay between the
// threshold crossings).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include <fmt/format.h>

#include "bissc_generator.h"
#include "bissc_test_util.h"
#include "capture/capture_reader.h"
#include "capture/scope_csv_writer.h"
#include "core/session.h"
#include "support/decode_events.h"
#include "support/paths.h"

namespace busdecode {
namespace {

std::vector<Event> decodeFile(const std::string& path, const std::string& bits) {
    test::registerBissc();
    return test::eventsOfType(
        test::decodeEvents(path, {{"bissc", {{"ma", "MA"}, {"sl", "SLO"}}, {{"bits", bits}}}}),
        "frame");
}

TEST(BisscScope, EveryDialectDecodesEveryFrameWithItsLineDelay) {
    BisscGenConfig cfg;
    cfg.clock_hz = 1e6;
    cfg.bits = 26;
    cfg.line_delay_ns = 1200;
    cfg.timeout_ns = 5000;
    cfg.idle_ns = 3000;
    BisscGenerator gen(cfg);
    std::mt19937_64 rng(11);
    for (int i = 0; i < 8; ++i) {
        BisscFrameSpec f;
        f.data = rng() & ((1u << 26) - 1);
        gen.addFrame(f);
    }
    const Waveform w = gen.build();
    for (const ScopeDialect d : kScopeDialects) {
        for (const double snr : {20.0, 26.0}) {
            SCOPED_TRACE(fmt::format("{} at {} dB", scopeDialectName(d), snr));
            AnalogStyle s;
            s.sample_ns = 10;
            s.low_v = 0;
            s.high_v = 5;
            s.offset_v = 0.7;
            s.rise_ns = 200;
            s.snr_db = snr;
            s.ringing = 0.15;
            s.ring_ns = 40;
            s.seed = std::uint64_t(d) * 100 + std::uint64_t(snr);
            const std::string p =
                test::tempDir() + fmt::format("/bissc_{}_{}.csv", scopeDialectName(d), snr);
            writeScopeCsv(w, p, d, s);
            const auto frames = decodeFile(p, "26");
            ASSERT_EQ(frames.size(), gen.frames().size());
            for (std::size_t i = 0; i < frames.size(); ++i) {
                const Event& e = frames[i];
                SCOPED_TRACE(fmt::format("frame {}: {}", i, e.summary));
                EXPECT_TRUE(e.errors.empty());
                EXPECT_EQ(std::uint64_t(test::intField(e, "position")), gen.frames()[i].spec.data);
                EXPECT_EQ(test::intField(e, "crc_ok"), 1);
                const double delay = asDouble(*e.get("line_delay_ns"));
                EXPECT_NEAR(delay, cfg.line_delay_ns, cfg.line_delay_ns / 100);
            }
        }
    }
}

}  // namespace
}  // namespace busdecode
