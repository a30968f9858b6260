// The example captures in captures/tmc8100_* are what the generator makes: read back from
// the committed VCD files, they decode to exactly the events of the in-memory truth.
#include <gtest/gtest.h>

#include <filesystem>

#include "core/registry.h"
#include "core/session.h"
#include "event_expect.h"
#include "support/decode_events.h"
#include "support/paths.h"
#include "tmc8100_examples.h"

using namespace busdecode;
using namespace busdecode::test;

namespace {
std::string describe(const Event& e) {
    std::string s =
        e.proto + "/" + e.type + " " + std::to_string(e.start) + "-" + std::to_string(e.end);
    for (const auto& f : e.fields)
        s += " " + f.key + "=" + show(f.value);
    for (const auto& x : e.errors)
        s += " !" + x;
    return s;
}
}  // namespace

TEST(Tmc8100Examples, CommittedCapturesDecodeLikeTheTruth) {
    registerDecoders();
    const auto examples = tmc8100Examples();
    ASSERT_EQ(examples.size(), 4u);
    for (const auto& ex : examples) {
        SCOPED_TRACE(ex.file);
        bool decodable = true;
        for (const auto& r : ex.requests)
            decodable &= Registry::instance().find(r.proto) != nullptr;
        if (!decodable) continue;  // an encoder decoder this build does not have
        const std::string path = examplePath(ex.file);
        ASSERT_TRUE(std::filesystem::exists(path)) << "run make_examples captures tmc8100";
        auto truth = decodeWaveform(ex.wave, ex.requests);
        const auto events = decodeEvents(path, ex.requests);
        ASSERT_EQ(events.size(), truth.size());
        ASSERT_GT(truth.size(), 20u);
        for (std::size_t i = 0; i < truth.size(); ++i)
            EXPECT_EQ(describe(events[i]), describe(truth[i]));
    }
}

TEST(Tmc8100Examples, FaultsCaptureCarriesOneOfEachFault) {
    registerDecoders();
    const auto examples = tmc8100Examples();
    auto events = decodeWaveform(examples[1].wave, examples[1].requests);
    std::map<std::string, int> errors;
    for (const auto& e : events)
        for (const auto& x : e.errors)
            errors[e.proto + ":" + x]++;
    const std::map<std::string, int> want = {{"tmc8100:inconsistent", 1},
                                             {"tmc8100:ssi_mismatch", 1},
                                             {"tmc8100:avail_low", 1},
                                             {"tmc8100:unexpected_avail", 1},
                                             {"tmc8100:replies_pending", 1}};
    EXPECT_EQ(errors, want);
}
