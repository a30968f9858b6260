// Every field of every event is one its decoder declares, with a value of the declared
// kind (fuzz/harness/declared_fields.h): on every example capture of every decoder here,
// and on hostile traffic and the fuzzers' inputs through fuzz::decodeChecked().
#include <gtest/gtest.h>

#include <iostream>

#include "core/registry.h"
#include "declared_fields.h"
#include "example.h"
#include "fuzz_harness.h"
#include "support/decode_events.h"

namespace busdecode {
namespace {

TEST(DeclaredFields, EveryExampleCapturesFieldsAreDeclaredWithTheirKinds) {
    fuzz::registerDecoders();
    std::size_t captures = 0, events = 0;
    for (const auto& [id, list] : listedExamples()) {
        for (const ExampleCapture& ex : list()) {
            SCOPED_TRACE(ex.file);
            for (const Event& e : test::decodeForFields(ex.wave, ex.requests)) {
                EXPECT_EQ(fuzz::undeclaredField(e, ex.requests), "");
                ++events;
            }
            ++captures;
        }
    }
    std::cout << captures << " example captures, " << events << " events checked\n";
    EXPECT_EQ(listedExamples().size(), Registry::instance().all().size());
    EXPECT_GT(captures, 10u);
    EXPECT_GT(events, 400u);
}

Event bisscFrame() {
    Event e;
    e.proto = "bissc";
    e.type = "frame";
    return e;
}

TEST(DeclaredFields, AnUndeclaredFieldOrAValueOfAnotherKindIsFound) {
    fuzz::registerDecoders();
    Event e = bisscFrame();
    e.add("position", std::uint64_t(5));
    e.add("crc_ok", Null{});
    EXPECT_EQ(fuzz::undeclaredField(e, {}), "");
    e.add("clock_hz", std::int64_t(1000000));  // declared a number
    EXPECT_EQ(fuzz::undeclaredField(e, {}),
              "bissc frame: field 'clock_hz' is not of its declared kind number");
    Event extra = bisscFrame();
    extra.add("speed", 1.0);
    EXPECT_EQ(fuzz::undeclaredField(extra, {}), "bissc frame: field 'speed' is not declared");
    Event type = bisscFrame();
    type.type = "burst";
    EXPECT_EQ(fuzz::undeclaredField(type, {}), "bissc burst: the type is not declared");
}

TEST(DeclaredFields, FieldsNamedByAnOptionAreDeclaredByIt) {
    fuzz::registerDecoders();
    Event e;
    e.proto = "ssi";
    e.type = "frame";
    e.add("low_quality", true);
    DecoderRequest named;
    named.proto = "ssi";
    named.options["status_bits"] = "out_of_range@23,low_quality@22";
    EXPECT_EQ(fuzz::undeclaredField(e, {named}), "");
    EXPECT_EQ(fuzz::undeclaredField(e, {}), "ssi frame: field 'low_quality' is not declared");
    e.fields.front().value = std::int64_t(1);
    EXPECT_EQ(fuzz::undeclaredField(e, {named}),
              "ssi frame: field 'low_quality' is not of its declared kind bool");
}

}  // namespace
}  // namespace busdecode
