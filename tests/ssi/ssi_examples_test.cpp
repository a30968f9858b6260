// The committed example captures (captures/ssi_*) are what the generator makes: each
// decodes to the generator's truth, its golden output (ssi_*.golden.jsonl) is exactly
// what the decoder prints for it, and the `decode` CLI prints the same.
#include <gtest/gtest.h>

#include <filesystem>

#include <fmt/format.h>

#include "core/session.h"
#include "sinks/jsonl_file.h"
#include "ssi_examples.h"
#include "ssi_test_util.h"
#include "support/decode_events.h"
#include "support/paths.h"

using namespace busdecode;
using namespace busdecode::ssitest;

namespace {

std::vector<Event> decodeFileFrames(const SsiExample& ex) {
    registerSsi();
    return test::eventsOfType(test::decodeEvents(test::examplePath(ex.file), ex.requests), "frame");
}

}  // namespace

TEST(SsiExamples, CommittedCapturesDecodeToTheTruth) {
    const auto examples = ssiExamples();
    ASSERT_EQ(examples.size(), 4u);
    for (const auto& ex : examples) {
        SCOPED_TRACE(ex.file);
        const auto frames = decodeFileFrames(ex);
        // The truncated burst of the ring-shift example ends inside a repeat-free word.
        expectTruth(frames, SsiGenerated{ex.wave, ex.truth}, {"tm_missing"});
        const auto memory = decodeFrames(ex.wave, ex.options());
        ASSERT_EQ(memory.size(), frames.size());
        for (std::size_t i = 0; i < frames.size(); ++i)
            EXPECT_EQ(describe(frames[i]), describe(memory[i]));
    }
}

TEST(SsiExamples, WhatTheExamplesShow) {
    const auto examples = ssiExamples();
    auto tmc = decodeFileFrames(examples[0]);
    ASSERT_EQ(tmc.size(), 5u);
    EXPECT_TRUE(flag(tmc[2], "reread"));
    EXPECT_EQ(u64(tmc[2], "raw"), u64(tmc[1], "raw"));
    EXPECT_TRUE(flag(tmc[3], "low_quality"));
    EXPECT_TRUE(flag(tmc[4], "out_of_range"));
    EXPECT_EQ(u64(tmc[4], "st"), 0x8000u);

    auto pos = decodeFileFrames(examples[1]);
    ASSERT_EQ(pos.size(), 3u);
    EXPECT_EQ(u64(pos[0], "raw"), 0x010014EDu);
    EXPECT_EQ(u64(pos[0], "mt"), 1u);
    EXPECT_EQ(u64(pos[0], "st"), 0x4EDu);
    EXPECT_NEAR(asDouble(*pos[0].get("angle")), 110.83, 0.005);

    auto ring = decodeFileFrames(examples[2]);
    ASSERT_EQ(ring.size(), 4u);
    EXPECT_EQ(i64(ring[0], "repeats"), 3);
    EXPECT_TRUE(ring[1].hasError("repeat_mismatch"));
    EXPECT_EQ(std::get<std::vector<std::int64_t>>(*ring[1].get("repeat_diff_bits")),
              (std::vector<std::int64_t>{4}));
    EXPECT_EQ(i64(ring[2], "repeats"), 2);
    EXPECT_TRUE(ring[3].hasError("short_frame"));
    for (const auto& e : ring)
        EXPECT_NEAR(asDouble(*e.get("delay_ns")), 400, 50);
}

TEST(SsiExamples, GoldenOutputsMatch) {
    registerSsi();
    for (const auto& ex : ssiExamples()) {
        SCOPED_TRACE(ex.file);
        const std::string golden = test::readFile(test::examplePath(goldenPathFor(ex.file)));
        EXPECT_EQ(decodeFileToJsonl(test::examplePath(ex.file), "ssi", ex.options()), golden);
        EXPECT_NE(golden.find("\"type\":\"summary\""), std::string::npos);
    }
}

TEST(SsiExamples, DecodeCliPrintsTheGoldenOutput) {
    for (const auto& ex : ssiExamples()) {
        SCOPED_TRACE(ex.file);
        std::vector<std::string> args = {test::examplePath(ex.file), "--proto", "ssi", "--format",
                                         "jsonl"};
        for (const auto& [k, v] : ex.options()) {
            args.push_back("--opt");
            args.push_back(k + "=" + v);
        }
        const auto r = test::runDecode(args);
        ASSERT_EQ(r.status, 0) << r.err;
        EXPECT_EQ(r.out, test::readFile(test::examplePath(goldenPathFor(ex.file))));
    }
}
