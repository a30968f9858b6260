#include "ssi_test_util.h"

#include <gtest/gtest.h>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "core/registry.h"
#include "core/session.h"
#include "ssi_info.h"

namespace busdecode::ssitest {

void registerSsi() {
    Registry::instance().add(makeSsiFactory());
}

std::vector<Event> decodeFrames(const Waveform& w, std::map<std::string, std::string> opts) {
    registerSsi();
    DecoderRequest r;
    r.proto = "ssi";
    r.options = std::move(opts);
    std::vector<Event> frames;
    for (auto& e : decodeWaveform(w, {r}))
        if (e.type == "frame") frames.push_back(std::move(e));
    return frames;
}

std::uint64_t u64(const Event& e, const char* key) {
    const Value* v = e.get(key);
    if (!v) return ~std::uint64_t(0);
    if (auto* u = std::get_if<std::uint64_t>(v)) return *u;
    return std::uint64_t(asInt(*v));
}

std::int64_t i64(const Event& e, const char* key) {
    const Value* v = e.get(key);
    return v ? asInt(*v) : -999;
}

bool flag(const Event& e, const char* key) {
    const Value* v = e.get(key);
    return v && std::holds_alternative<bool>(*v) && std::get<bool>(*v);
}

std::string describe(const Event& e) {
    return fmt::format("[{}..{}] {} errors={}", e.start, e.end, e.summary,
                       fmt::join(e.errors, ","));
}

void expectTruth(const std::vector<Event>& frames, const SsiGenerated& g,
                 const std::vector<std::string>& allowed) {
    ASSERT_EQ(frames.size(), g.frames.size());
    for (std::size_t i = 0; i < frames.size(); ++i) {
        const Event& e = frames[i];
        const SsiTruth& t = g.frames[i];
        SCOPED_TRACE(fmt::format("frame {}: {}", i, describe(e)));
        EXPECT_EQ(e.start, t.start);
        EXPECT_EQ(e.end, t.end);
        EXPECT_EQ(u64(e, "raw"), t.raw);
        EXPECT_EQ(i64(e, "bits"), t.bits);
        EXPECT_EQ(e.hasError("short_frame"), t.short_frame);
        if (!t.short_frame) {
            EXPECT_EQ(i64(e, "repeats"), t.repeats);
            EXPECT_EQ(i64(e, "partial_bits"), t.partial_bits);
        }
        EXPECT_EQ(flag(e, "repeat_match"), t.repeat_match);
        EXPECT_EQ(e.hasError("repeat_mismatch"), !t.repeat_match);
        const Value* diff = e.get("repeat_diff_bits");
        ASSERT_NE(diff, nullptr);
        EXPECT_EQ(std::get<std::vector<std::int64_t>>(*diff), t.diff_bits);
        EXPECT_EQ(flag(e, "reread"), t.reread);
        const Value* tm = e.get("tm_ns");
        ASSERT_NE(tm, nullptr);
        if (t.tm_ns) {
            ASSERT_FALSE(isNull(*tm));
            const double tick_ns = g.wave.timebase.nsPerTick();
            EXPECT_NEAR(asDouble(*tm), *t.tm_ns, tick_ns / 2 + 0.5);
        } else {
            EXPECT_TRUE(isNull(*tm));
        }
        const Value* hz = e.get("clock_hz");
        ASSERT_NE(hz, nullptr);
        if (!isNull(*hz) && !t.short_frame) {
            EXPECT_NEAR(asDouble(*hz), t.clock_hz, t.clock_hz * 0.02);
        }
        for (const auto& err : e.errors) {
            if (err == "short_frame" || err == "repeat_mismatch") continue;
            EXPECT_NE(std::find(allowed.begin(), allowed.end(), err), allowed.end())
                << "unexpected error " << err;
        }
    }
}

}  // namespace busdecode::ssitest
