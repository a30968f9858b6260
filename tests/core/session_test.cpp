// The session's own jobs, checked with a tiny decoder defined here: role binding by
// alias, edges in time order, glitch filter, time-ordered release across decoders,
// and cross-decoder correlation.
#include <gtest/gtest.h>

#include "capture/capture_reader.h"
#include "core/block_decoding.h"
#include "core/event_window.h"
#include "core/registry.h"
#include "core/session.h"
#include "core/stacked.h"
#include "core/waveform.h"
#include "sinks/counting_sink.h"
#include "sinks/stream_sinks.h"
#include "support/decode_events.h"

using namespace busdecode;

namespace {

// Emits one event per rising edge on `in`, spanning from the previous falling edge;
// optionally asks to be correlated with the other decoder's events. A BlockDecoder, to
// see the hints a fast decoder is given (FastPathHints::fields_wanted, summaries_wanted).
class RiseDecoder : public BlockDecoder<RiseDecoder> {
public:
    explicit RiseDecoder(const Options& o) : tag_(o.text("tag")), correlate_(o.flag("correlate")) {}
    void start(const DecoderContext& ctx) override {
        Decoder::start(ctx);
        fields_wanted.push_back(fieldsWanted());
        summaries_wanted.push_back(summariesWanted());
    }
    void edge(Tick t, int, bool level) override {
        if (!level) {
            fell_ = t;
            busyFrom(t);
            return;
        }
        Event e;
        e.proto = "rise";
        e.type = tag_;
        e.start = fell_ == kNoTick ? t : fell_;
        e.end = t;
        e.wants_correlation = correlate_;
        emit(std::move(e));
        idle();
        fell_ = kNoTick;
    }
    void glitch(Tick t, int) override { glitches.push_back(t); }
    void finish(Tick) override {}
    void correlate(Event& e, const EventWindow& w) override {
        int n = 0;
        w.forEach("rise", "other", e.start, e.end + 1000, [&](const Event&) {
            ++n;
            return true;
        });
        e.set("peers", std::int64_t(n));
        // The window holds the other events, not the one being correlated.
        int self = 0;
        w.forEach(e.proto, e.type, e.start, e.start, [&](const Event& o) {
            self += o.end == e.end;
            return true;
        });
        e.set("self_seen", std::int64_t(self));
    }
    bool correlates() const override { return correlate_; }
    static std::vector<Tick> glitches;
    static std::vector<bool> fields_wanted;  // what each decoder was told at its start
    static std::vector<bool> summaries_wanted;

private:
    std::string tag_;
    bool correlate_;
    Tick fell_ = kNoTick;
};
std::vector<Tick> RiseDecoder::glitches;
std::vector<bool> RiseDecoder::fields_wanted;
std::vector<bool> RiseDecoder::summaries_wanted;

DecoderInfo riseInfo() {
    DecoderInfo d;
    d.id = "rise";
    d.roles = {{"in", true, {"input", "x"}, ""}};
    OptionSpec tag;
    tag.key = "tag";
    tag.kind = OptionSpec::Kind::String;
    tag.default_value = "edge";
    OptionSpec cor;
    cor.key = "correlate";
    cor.kind = OptionSpec::Kind::Bool;
    cor.default_value = "0";
    d.options = {tag, cor};
    return d;
}

struct RegisterRise {
    RegisterRise() {
        Registry::instance().add(std::make_shared<SimpleFactory<RiseDecoder>>(riseInfo()));
    }
} register_rise;

// Records every edge it is given. A BlockDecoder: as the only decoder it gets whole
// blocks through the inlined loop; beside another decoder, one edge() call per edge.
class TraceDecoder : public BlockDecoder<TraceDecoder> {
public:
    struct Seen {
        Tick t;
        int role;
        bool level;
        bool operator==(const Seen&) const = default;
    };
    explicit TraceDecoder(const Options&) {}
    void start(const DecoderContext& ctx) override {
        Decoder::start(ctx);
        lines_are_roles.push_back(hints().lines_are_roles);
    }
    void edge(Tick t, int role, bool level) override { trace.push_back({t, role, level}); }
    void finish(Tick) override {}
    static std::vector<Seen> trace;
    static std::vector<bool> lines_are_roles;  // FastPathHints::lines_are_roles, per start()
};
std::vector<TraceDecoder::Seen> TraceDecoder::trace;
std::vector<bool> TraceDecoder::lines_are_roles;

DecoderInfo traceInfo() {
    DecoderInfo d;
    d.id = "trace";
    d.roles = {{"p", false, {}, ""}, {"q", false, {}, ""}};
    return d;
}

struct RegisterTrace {
    RegisterTrace() {
        Registry::instance().add(std::make_shared<SimpleFactory<TraceDecoder>>(traceInfo()));
    }
} register_trace;

// Fills the events it emits from newEvent(), alternately with and without a field,
// an error and a summary: the session recycles output events, and nothing of an odd
// event may reach the even one filled in its storage.
class AlternateDecoder : public Decoder {
public:
    explicit AlternateDecoder(const Options&) : Decoder("alternate") {}
    void edge(Tick t, int, bool level) override {
        if (!level) return;
        EventPtr owned = newEvent("rise", t, t);
        Event& e = *owned;
        if (++count_ % 2 == 1) {
            e.add("odd", std::int64_t(count_));
            e.error("odd");
            e.summary = "an odd one, with a summary longer than a short string";
            e.instance = "kept?";
        }
        emit(std::move(owned));
    }
    void finish(Tick) override {}

private:
    int count_ = 0;
};

DecoderInfo alternateInfo() {
    DecoderInfo d;
    d.id = "alternate";
    d.roles = {{"in", true, {}, ""}};
    return d;
}

struct RegisterAlternate {
    RegisterAlternate() {
        Registry::instance().add(
            std::make_shared<SimpleFactory<AlternateDecoder>>(alternateInfo()));
    }
} register_alternate;

Waveform twoLines() {
    WaveBuilder b(Timebase{1, 1'000'000'000}, {"top.a", "top.input"}, {1, 1});
    b.set(0, 100, false);
    b.set(0, 200, true);
    b.set(1, 150, false);
    b.set(1, 250, true);
    b.set(1, 300, false);
    b.set(1, 303, true);  // a 3 ns glitch
    b.set(0, 400, false);
    b.set(0, 500, true);
    return b.build(1000);
}

}  // namespace

TEST(Session, BindsByAliasAndExplicitMap) {
    auto w = twoLines();
    auto ev = decodeWaveform(w, {{"rise", {}, {}}});  // alias "input"
    ASSERT_EQ(ev.size(), 2u);
    EXPECT_EQ(ev[0].start, 150);
    EXPECT_EQ(ev[0].end, 250);
    auto ev2 = decodeWaveform(w, {{"rise", {{"in", "a"}}, {}}});
    ASSERT_EQ(ev2.size(), 2u);
    EXPECT_EQ(ev2[0].start, 100);
    auto ev3 = decodeWaveform(w, {{"rise", {{"in", "0"}}, {}}});  // by index
    EXPECT_EQ(ev3[0].start, 100);
}

TEST(Session, UnboundRoleListsSignals) {
    WaveBuilder b(Timebase{}, {"foo", "bar"}, {1, 1});
    auto w = b.build(10);
    try {
        decodeWaveform(w, {{"rise", {}, {}}});
        FAIL() << "expected InputError";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("role 'in' is not bound"), std::string::npos);
        EXPECT_NE(std::string(e.what()).find("signals: foo, bar"), std::string::npos);
    }
}

TEST(Session, GlitchFilterRemovesShortPulsesAndReportsThem) {
    RiseDecoder::glitches.clear();
    auto w = twoLines();
    auto ev = decodeWaveform(w, {{"rise", {}, {{"glitch_ns", "5"}}}});
    ASSERT_EQ(ev.size(), 1u);  // the 3 ns pulse is gone
    ASSERT_EQ(RiseDecoder::glitches.size(), 1u);
    EXPECT_EQ(RiseDecoder::glitches[0], 300);
    auto ev2 = decodeWaveform(w, {{"rise", {}, {{"glitch_ns", "2"}}}});
    EXPECT_EQ(ev2.size(), 2u);  // a 2 ns filter keeps it
}

TEST(Session, EventsFromSeveralDecodersComeOutInStartOrder) {
    auto w = twoLines();
    auto ev = decodeWaveform(
        w, {{"rise", {{"in", "a"}}, {{"tag", "other"}}}, {"rise", {{"in", "input"}}, {}}});
    ASSERT_EQ(ev.size(), 4u);
    for (std::size_t i = 1; i < ev.size(); ++i)
        EXPECT_LE(ev[i - 1].start, ev[i].start);
    EXPECT_EQ(ev[0].instance, "rise#1");
    EXPECT_EQ(ev[1].instance, "rise#2");
}

TEST(Session, CorrelationSeesOtherDecodersEventsByTime) {
    auto w = twoLines();
    auto ev = decodeWaveform(w, {{"rise", {{"in", "a"}}, {{"tag", "other"}}},
                                 {"rise", {{"in", "input"}}, {{"correlate", "1"}}}});
    int checked = 0;
    for (const auto& e : ev) {
        if (e.type != "edge") continue;
        ASSERT_TRUE(e.has("peers"));
        EXPECT_EQ(asInt(*e.get("self_seen")), 0);
        ++checked;
    }
    EXPECT_EQ(checked, 2);
    // The first "edge" event spans 150..250; its window 150..1250 holds one "other"
    // event (400..500), which had not been emitted yet when the "edge" event was.
    const Event* first = nullptr;
    for (const auto& e : ev)
        if (e.type == "edge" && !first) first = &e;
    EXPECT_EQ(asInt(*first->get("peers")), 1);
}

namespace {

// What a sink that never reads fields reads: summaries only, as text output.
constexpr CountingSink::Reads kSummariesOnly{.fields = false};

// Runs a session over twoLines() with these decoders and sinks: RiseDecoder's vectors
// then hold what each decoder was told.
void runWith(const std::vector<DecoderRequest>& requests, const std::vector<OutputSink*>& sinks) {
    const Waveform w = twoLines();
    auto reader = memoryReader(w);
    Session s(requests, *reader, "memory");
    for (auto* sink : sinks)
        s.addSink(sink);
    RiseDecoder::fields_wanted.clear();
    RiseDecoder::summaries_wanted.clear();
    s.run();
}

// fieldsWanted(), per decoder.
std::vector<bool> fieldsWantedWith(const std::vector<DecoderRequest>& requests,
                                   const std::vector<OutputSink*>& sinks) {
    runWith(requests, sinks);
    return RiseDecoder::fields_wanted;
}

// summariesWanted(), per decoder.
std::vector<bool> summariesWantedWith(const std::vector<DecoderRequest>& requests,
                                      const std::vector<OutputSink*>& sinks) {
    runWith(requests, sinks);
    return RiseDecoder::summaries_wanted;
}

}  // namespace

TEST(Session, FieldsAreWantedWhenASinkReadsThemOrADecoderCorrelates) {
    const std::vector<DecoderRequest> two = {{"rise", {{"in", "a"}}, {{"tag", "other"}}},
                                             {"rise", {{"in", "input"}}, {}}};
    const std::vector<DecoderRequest> correlating = {
        {"rise", {{"in", "a"}}, {{"tag", "other"}}},
        {"rise", {{"in", "input"}}, {{"correlate", "1"}}}};
    CountingSink text(kSummariesOnly), text2(kSummariesOnly);
    CountingSink json;
    EXPECT_EQ(fieldsWantedWith(two, {&text}), (std::vector<bool>{false, false}));
    EXPECT_EQ(text.events(), 4u);  // the events still come out
    EXPECT_EQ(fieldsWantedWith(two, {&text, &text2}), (std::vector<bool>{false, false}));
    EXPECT_EQ(fieldsWantedWith(two, {&text, &json}), (std::vector<bool>{true, true}));
    EXPECT_EQ(fieldsWantedWith(two, {&json}), (std::vector<bool>{true, true}));
    // A correlating decoder reads the other decoder's events: all of them get fields.
    EXPECT_EQ(fieldsWantedWith(correlating, {&text}), (std::vector<bool>{true, true}));
}

TEST(Session, TextOutputReadsNoFieldsJsonDoes) {
    EXPECT_FALSE(makeTextSink(stdout)->readsFields());
    EXPECT_TRUE(makeJsonlSink(stdout)->readsFields());
}

TEST(Session, SummariesAreWantedWhenASinkReadsThem) {
    const std::vector<DecoderRequest> correlating = {
        {"rise", {{"in", "a"}}, {{"tag", "other"}}},
        {"rise", {{"in", "input"}}, {{"correlate", "1"}}}};
    CountingSink text(kSummariesOnly);
    CountingSink report;               // reads both, as the HTML report
    test::FieldCollector json, json2;  // reads fields, never summaries (as jsonl)
    EXPECT_EQ(summariesWantedWith(correlating, {&json}), (std::vector<bool>{false, false}));
    EXPECT_EQ(summariesWantedWith(correlating, {&json, &json2}), (std::vector<bool>{false, false}));
    EXPECT_EQ(summariesWantedWith(correlating, {&json, &text}), (std::vector<bool>{true, true}));
    EXPECT_EQ(summariesWantedWith(correlating, {&report, &json}), (std::vector<bool>{true, true}));
    EXPECT_EQ(summariesWantedWith(correlating, {}), (std::vector<bool>{false, false}));
}

TEST(Session, TextOutputReadsSummariesJsonDoesNot) {
    EXPECT_TRUE(makeTextSink(stdout)->readsSummaries());
    EXPECT_FALSE(makeJsonlSink(stdout)->readsSummaries());
}

TEST(Session, AStackedDecodersLowerOneAlwaysAddsFields) {
    // The upper decoder reads the lower one's fields, whatever the output wants.
    LowerStack stack("rise", Options{}, {0}, [](Event&&) {});
    DecoderContext upper;
    upper.initial_levels = {1};
    RiseDecoder::fields_wanted.clear();
    stack.start(upper);
    EXPECT_EQ(RiseDecoder::fields_wanted, std::vector<bool>{true});
}

TEST(Session, BadOptionNamesDecoderAndValidValues) {
    auto w = twoLines();
    try {
        decodeWaveform(w, {{"rise", {}, {{"correlate", "maybe"}}}});
        FAIL();
    } catch (const InputError& e) {
        EXPECT_STREQ(e.what(), "decoder rise: option correlate=maybe: expected 0 or 1");
    }
}

// An Edge names at most kMaxSelectedLines lines: a session mapping one more is refused
// with an error naming the capture, not left to wrap the line numbers.
TEST(Session, RefusesMoreMappedSignalsThanAnEdgeCanName) {
    Waveform w;
    w.timebase = Timebase{1, 1'000'000'000};
    for (std::size_t i = 0; i <= kMaxSelectedLines; ++i) {
        w.names.push_back("top.s" + std::to_string(i));
        w.initial.push_back(0);
    }
    std::vector<DecoderRequest> requests;
    for (std::size_t i = 0; i < kMaxSelectedLines; ++i)
        requests.push_back({"rise", {{"in", "s" + std::to_string(i)}}, {}});
    {
        auto reader = memoryReader(w);
        Session s(requests, *reader, "memory");  // 128: accepted
    }
    requests.push_back({"rise", {{"in", "s128"}}, {}});
    auto reader = memoryReader(w);
    try {
        Session s(requests, *reader, "memory");
        FAIL() << "129 mapped signals accepted";
    } catch (const InputError& e) {
        EXPECT_STREQ(e.what(), "memory: more than 128 signals mapped");
    }
}

TEST(Session, BlockPathDeliversWhatThePerEdgePathDoes) {
    auto w = twoLines();
    // A repeated level (line 0 is already low at 120) is not an edge on either path.
    w.edges.insert(w.edges.begin() + 1, Edge{120, 0, 0});
    const std::vector<TraceDecoder::Seen> want = {{100, 1, false}, {150, 0, false}, {200, 1, true},
                                                  {250, 0, true},  {300, 0, false}, {303, 0, true},
                                                  {400, 1, false}, {500, 1, true}};
    const DecoderRequest trace{"trace", {{"p", "input"}, {"q", "a"}}, {}};
    TraceDecoder::trace.clear();
    decodeWaveform(w, {trace});  // the only decoder: whole blocks
    EXPECT_EQ(TraceDecoder::trace, want);
    TraceDecoder::trace.clear();
    decodeWaveform(w, {trace, {"rise", {{"in", "a"}}, {}}});  // two decoders: edge by edge
    EXPECT_EQ(TraceDecoder::trace, want);
}

TEST(Session, LinesAreRolesWhenTheBlocksHandEachRoleItsOwnLine) {
    const Waveform w = twoLines();
    const auto seen = [&w](const std::vector<DecoderRequest>& requests) {
        TraceDecoder::lines_are_roles.clear();
        decodeWaveform(w, requests);
        return TraceDecoder::lines_are_roles;
    };
    // The only decoder, both roles bound: the session selects the lines in role order,
    // whatever their order in the capture.
    EXPECT_EQ(seen({{"trace", {{"p", "input"}, {"q", "a"}}, {}}}), std::vector<bool>{true});
    EXPECT_EQ(seen({{"trace", {{"p", "a"}, {"q", "input"}}, {}}}), std::vector<bool>{true});
    // Its first role unbound: the one line selected carries role 1.
    EXPECT_EQ(seen({{"trace", {{"q", "a"}}, {}}}), std::vector<bool>{false});
    // Beside another decoder: edge by edge, no blocks.
    EXPECT_EQ(seen({{"trace", {{"p", "input"}, {"q", "a"}}, {}}, {"rise", {{"in", "a"}}, {}}}),
              std::vector<bool>{false});
}

TEST(Session, RecycledEventsCarryNothingOfTheirLastUse) {
    // Events are output between edge blocks: enough pulses for several blocks, so that
    // later events are filled in the storage of output ones.
    constexpr int kPulses = 3 * int(kEdgeBlockSize) / 2;
    WaveBuilder b(Timebase{1, 1'000'000'000}, {"top.in"}, {0});
    for (int i = 0; i < kPulses; ++i) {
        b.set(0, 10 * i + 2, true);
        b.set(0, 10 * i + 7, false);
    }
    const auto ev = decodeWaveform(b.build(10 * kPulses + 10), {{"alternate", {{"in", "in"}}, {}}});
    ASSERT_EQ(ev.size(), std::size_t(kPulses));
    for (std::size_t i = 0; i < ev.size(); ++i) {
        const Event& e = ev[i];
        EXPECT_EQ(e.proto, "alternate");
        EXPECT_EQ(e.instance, "alternate") << i;  // set by the session every time
        EXPECT_EQ(e.start, Tick(10 * i + 2));
        if (i % 2 == 0) {
            ASSERT_EQ(e.fields.size(), 1u) << i;
            EXPECT_EQ(e.errors, std::vector<std::string>{"odd"}) << i;
            EXPECT_FALSE(e.summary.empty()) << i;
        } else {
            EXPECT_TRUE(e.fields.empty()) << i;
            EXPECT_TRUE(e.errors.empty()) << i;
            EXPECT_TRUE(e.summary.empty()) << i;
        }
    }
}

TEST(Event, ResetLeavesAFreshEventKeepingStorage) {
    Event e;
    e.proto = "proto";
    e.type = "type";
    e.start = 5;
    e.end = 9;
    e.add("a", std::int64_t(1)).add("b", std::string("a string value too long for SSO"));
    e.error("crc");
    e.summary = "a summary longer than the short string buffer";
    e.instance = "proto#2";
    e.wants_correlation = true;
    const auto field_capacity = e.fields.capacity();
    e.reset();
    const Event fresh;
    EXPECT_EQ(e.proto, fresh.proto);
    EXPECT_EQ(e.type, fresh.type);
    EXPECT_EQ(e.start, fresh.start);
    EXPECT_EQ(e.end, fresh.end);
    EXPECT_TRUE(e.fields.empty());
    EXPECT_TRUE(e.errors.empty());
    EXPECT_EQ(e.summary, fresh.summary);
    EXPECT_EQ(e.instance, fresh.instance);
    EXPECT_EQ(e.wants_correlation, fresh.wants_correlation);
    EXPECT_EQ(e.fields.capacity(), field_capacity);
    // A member added to Event changes its size: reset() must then clear it too.
    EXPECT_EQ(sizeof(Event), 200u) << "Event changed: update Event::reset() and this test";
}
