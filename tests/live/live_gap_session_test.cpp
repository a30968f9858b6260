// A live run that drops samples, through the session: the gap comes out as a
// capture/samples_dropped event, and the UART byte cut by it carries the error, while the
// bytes around it do not.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdint>
#include <vector>

#include "capture/capture_reader.h"
#include "capture/live_edge_maker.h"
#include "core/registry.h"
#include "core/session.h"
#include "uart_decoder.h"

namespace busdecode {
namespace {

constexpr int kSamplesPerBit = 10;  // 100 kbaud at 1 MHz

// The samples of one 8N1 character on an idle-high line, with `idle` idle samples first.
std::vector<std::uint8_t> character(std::uint8_t value, int idle) {
    std::vector<std::uint8_t> out(std::size_t(idle), 1);
    auto bit = [&](int level) { out.insert(out.end(), kSamplesPerBit, std::uint8_t(level)); };
    bit(0);
    for (int i = 0; i < 8; ++i)
        bit(value >> i & 1);
    bit(1);
    return out;
}

// The blocks a LiveEdgeMaker queued, as a capture of one line "rx" at 1 MHz.
class QueuedCapture : public CaptureReader {
public:
    explicit QueuedCapture(LiveEdgeQueue& q, std::vector<std::uint8_t> levels)
        : q_(q), levels_(std::move(levels)) {}
    const std::vector<SignalInfo>& signals() const override { return signals_; }
    Timebase timebase() const override { return Timebase{1, 1'000'000}; }
    std::string formatName() const override { return "live"; }
    void select(const std::vector<LineRef>&) override {}
    std::vector<std::uint8_t> initialLevels() override { return levels_; }
    Tick startTick() const override { return 0; }
    bool next(EdgeBlock& block) override {
        block.clear();
        std::atomic<bool> empty_ends_it{true};
        return q_.pop(block, &empty_ends_it);
    }
    Tick endTick() const override { return 1000; }

private:
    LiveEdgeQueue& q_;
    std::vector<std::uint8_t> levels_;
    std::vector<SignalInfo> signals_{{"rx", "rx"}};
};

struct Collect : OutputSink {
    void onEvent(const Event& e, const CaptureFacts&) override { events.push_back(e); }
    std::vector<Event> events;
};

TEST(LiveGap, TheEventCutByDroppedSamplesCarriesTheError) {
    Registry::instance().add(makeUartFactory());
    LiveEdgeQueue q(64, 1 << 20);
    LiveEdgeMaker m;
    m.select({0});
    const auto a = character(0x41, 20), b = character(0x42, 20), c = character(0x43, 20);
    m.addPacket(a.data(), a.size(), 1, q);
    // 'B' loses its middle: the first 45 samples (idle, start bit and two data bits) are
    // delivered, the next 40 dropped.
    m.addPacket(b.data(), 45, 1, q);
    m.dropPacket(b.data() + 45, 40, 1, q);
    m.addPacket(b.data() + 85, b.size() - 85, 1, q);
    m.addPacket(c.data(), c.size(), 1, q);
    QueuedCapture capture(q, m.initialLevels());
    Session session({{"uart", {{"rx", "rx"}}, {{"baud", "100000"}}}}, capture, "live");
    Collect out;
    session.addSink(&out);
    session.run();

    std::vector<const Event*> bytes, gaps;
    for (const Event& e : out.events)
        (e.proto == "capture" ? gaps : bytes).push_back(&e);
    ASSERT_EQ(gaps.size(), 1u);
    EXPECT_EQ(gaps[0]->type, "samples_dropped");
    const Tick gap_first = Tick(a.size() + 45), gap_end = gap_first + 40;
    EXPECT_EQ(gaps[0]->start, gap_first);
    EXPECT_EQ(gaps[0]->end, gap_end);
    ASSERT_GE(bytes.size(), 3u);
    EXPECT_EQ(asInt(*bytes.front()->get("value")), 0x41);
    EXPECT_TRUE(bytes.front()->errors.empty());
    EXPECT_EQ(asInt(*bytes.back()->get("value")), 0x43);
    EXPECT_TRUE(bytes.back()->errors.empty());
    int marked = 0;
    for (const Event* e : bytes) {
        const bool reaches = e->start <= gap_end && gap_first <= e->end;
        EXPECT_EQ(e->hasError("samples_dropped"), reaches) << e->start << " " << e->end;
        marked += reaches;
    }
    EXPECT_GE(marked, 1);
    // In time order, the gap among the bytes.
    for (std::size_t i = 1; i < out.events.size(); ++i)
        EXPECT_LE(out.events[i - 1].start, out.events[i].start);
}

}  // namespace
}  // namespace busdecode
