// The committed example captures (captures/bissc_*) are exactly what the generator makes
// now, decode to the generator's truth, and their golden outputs (bissc_*.golden.jsonl)
// are what the decoder and the `decode` CLI print for them.
#include <gtest/gtest.h>

#include "bissc_examples.h"
#include "bissc_test_util.h"
#include "sinks/jsonl_file.h"
#include "support/decode_events.h"
#include "support/paths.h"

using namespace busdecode;
using namespace busdecode::test;

namespace {

std::vector<Event> decodeFile(const BisscExample& ex) {
    registerBissc();
    return decodeEvents(examplePath(ex.file), ex.requests);
}

}  // namespace

TEST(BisscExamples, CommittedFilesAreWhatTheGeneratorMakes) {
    for (const auto& ex : bisscExamples()) {
        SCOPED_TRACE(ex.file);
        const std::string fresh = tempDir() + "/" + ex.file;
        writeExample(ex, fresh);
        // The VCD header carries no date, so the bytes must match.
        EXPECT_EQ(readFile(fresh), readFile(examplePath(ex.file)));
    }
}

TEST(BisscExamples, CommittedCapturesDecodeToTheTruth) {
    for (const auto& ex : bisscExamples()) {
        SCOPED_TRACE(ex.file);
        const auto events = decodeFile(ex);
        const auto frames = ofType(events, "frame");
        ASSERT_EQ(frames.size(), ex.truth.frames.size());
        const double ns_per_tick = ex.wave.timebase.nsPerTick();
        for (std::size_t i = 0; i < frames.size(); ++i) {
            SCOPED_TRACE(i);
            const auto& t = ex.truth.frames[i];
            EXPECT_NEAR(double(frames[i].start), double(t.start), 1.0 / ns_per_tick + 1);
            if (t.truncated) {
                EXPECT_FALSE(frames[i].errors.empty());
                continue;
            }
            EXPECT_EQ(std::get<std::uint64_t>(*frames[i].get("position")), t.spec.data);
            EXPECT_EQ(std::get<bool>(*frames[i].get("crc_ok")), t.crc_ok);
            EXPECT_EQ(intField(frames[i], "cdm"), t.spec.cdm);
            EXPECT_EQ(intField(frames[i], "cds"), t.spec.cds);
            EXPECT_EQ(intField(frames[i], "nE"), t.spec.ne);
            EXPECT_EQ(intField(frames[i], "proc_cycles"), t.spec.proc_cycles);
        }
        std::vector<Event> control;
        for (const auto& e : events)
            if (e.type != "frame") control.push_back(e);
        ASSERT_EQ(control.size(), ex.truth.control.size());
        for (std::size_t i = 0; i < control.size(); ++i) {
            EXPECT_EQ(intField(control[i], "address"), ex.truth.control[i].address);
            EXPECT_EQ(intField(control[i], "data"), ex.truth.control[i].data);
            EXPECT_TRUE(std::get<bool>(*control[i].get("crc_ok")));
        }
        // The file decodes exactly like the in-memory waveform it was written from.
        const auto memory = decodeBissc(ex.wave, ex.options());
        ASSERT_EQ(memory.size(), events.size());
        for (std::size_t i = 0; i < events.size(); ++i)
            EXPECT_EQ(memory[i].summary, events[i].summary);
    }
}

TEST(BisscExamples, WhatTheExamplesShow) {
    const auto examples = bisscExamples();
    const auto reg = decodeFile(examples[0]);
    const auto accesses = ofType(reg, "register");
    ASSERT_EQ(accesses.size(), 3u);
    EXPECT_EQ(std::get<std::string>(*accesses[0].get("op")), "read");
    EXPECT_EQ(intField(accesses[0], "address"), 0x7E);
    EXPECT_EQ(intField(accesses[0], "data"), 0x12);
    EXPECT_EQ(intField(accesses[2], "address"), 0x49);  // sequential write, second byte
    EXPECT_EQ(intField(accesses[2], "busy_frames"), 2);

    const auto cable = ofType(decodeFile(examples[1]), "frame");
    ASSERT_EQ(cable.size(), 6u);
    for (const auto& f : cable) {
        EXPECT_NEAR(double(intField(f, "line_delay_ns")), 1200, 10);
        EXPECT_EQ(intField(f, "extra_clocks"), 4);
        EXPECT_TRUE(f.errors.empty());
    }

    const auto faults = ofType(decodeFile(examples[2]), "frame");
    ASSERT_EQ(faults.size(), 6u);
    EXPECT_TRUE(faults[0].errors.empty());
    EXPECT_EQ(faults[1].errors, std::vector<std::string>{"crc"});
    EXPECT_TRUE(faults[2].hasError("error_bit"));
    EXPECT_TRUE(faults[2].hasError("warning_bit"));
    EXPECT_TRUE(faults[3].hasError("short_frame"));
    EXPECT_EQ(intField(faults[4], "cdm"), 1);
    EXPECT_TRUE(std::get<bool>(*faults[5].get("hold_cdm")));
    EXPECT_TRUE(faults[5].errors.empty());
}

TEST(BisscExamples, GoldenOutputsMatch) {
    registerBissc();
    for (const auto& ex : bisscExamples()) {
        SCOPED_TRACE(ex.file);
        EXPECT_EQ(decodeFileToJsonl(examplePath(ex.file), "bissc", ex.options()),
                  readFile(examplePath(goldenPathFor(ex.file))));
    }
}

TEST(BisscExamples, DecodeCliPrintsTheGoldenOutput) {
    for (const auto& ex : bisscExamples()) {
        SCOPED_TRACE(ex.file);
        std::vector<std::string> args = {examplePath(ex.file), "--proto", "bissc", "--format",
                                         "jsonl"};
        for (const auto& [k, v] : ex.options()) {
            args.push_back("--opt");
            args.push_back(k + "=" + v);
        }
        const auto r = runDecode(args);
        ASSERT_EQ(r.status, 0) << r.err;
        EXPECT_EQ(r.out, readFile(examplePath(goldenPathFor(ex.file))));
    }
}

TEST(BisscExamples, DecodeCliWithBitsAutoPrintsTheGoldenOutput) {
    // Through the plugin the CLI loads: `--opt bits=auto` in place of each example's
    // width (26, 24, 32) prints the same golden lines.
    for (const auto& ex : bisscExamples()) {
        SCOPED_TRACE(ex.file);
        std::vector<std::string> args = {
            examplePath(ex.file), "--proto", "bissc", "--format", "jsonl", "--opt", "bits=auto"};
        for (const auto& [k, v] : ex.options()) {
            if (k == "bits") continue;
            args.push_back("--opt");
            args.push_back(k + "=" + v);
        }
        const auto r = runDecode(args);
        ASSERT_EQ(r.status, 0) << r.err;
        EXPECT_EQ(r.out, readFile(examplePath(goldenPathFor(ex.file))));
    }
}
