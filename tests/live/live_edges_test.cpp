// The acquisition side alone: samples become edges of the selected lines only, and a
// queue with no room drops whole packets, counts them, and resumes with the lines at
// their levels after the gap.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <tuple>
#include <vector>

#include "capture/live_device.h"
#include "capture/live_edge_maker.h"
#include "core/options.h"

namespace busdecode {
namespace {

std::vector<Edge> drain(LiveEdgeQueue& q) {
    std::vector<Edge> out;
    EdgeBlock b;
    std::atomic<bool> stop{true};  // return at once when empty
    while (q.pop(b, &stop))
        out.insert(out.end(), b.edges.begin(), b.edges.end());
    return out;
}

// One edge as {time, line, level}: compared whole, so a failure prints all three.
std::vector<std::array<std::uint64_t, 3>> asTriples(const std::vector<Edge>& edges) {
    std::vector<std::array<std::uint64_t, 3>> out;
    for (const Edge& e : edges)
        out.push_back({std::uint64_t(e.t), e.line, e.level});
    return out;
}

TEST(LiveEdges, OnlyChangesOfSelectedBits) {
    LiveEdgeQueue q(16, 1 << 20);
    LiveEdgeMaker m;
    m.select({2, 0});  // line 0 = bit 2, line 1 = bit 0
    const std::vector<std::uint8_t> s{0b000, 0b010, 0b100, 0b101, 0b101, 0b001};
    EXPECT_EQ(m.addPacket(s.data(), s.size(), 1, q), s.size());
    EXPECT_EQ(m.initialLevels(), (std::vector<std::uint8_t>{0, 0}));
    // Bit 1 is not selected.
    EXPECT_EQ(asTriples(drain(q)),
              (std::vector<std::array<std::uint64_t, 3>>{{2, 0, 1}, {3, 1, 1}, {5, 0, 0}}));
    EXPECT_EQ(q.counts().samples, 6u);
}

TEST(LiveEdges, WideWordsAndTheLimit) {
    LiveEdgeQueue q(16, 1 << 20);
    LiveEdgeMaker m;
    m.select({9});
    m.setLimit(3);
    // Two-byte words: bit 9 is bit 1 of the second byte.
    const std::vector<std::uint8_t> s{0, 0, 0, 2, 0, 0, 0, 2};
    EXPECT_EQ(m.addPacket(s.data(), 4, 2, q), 3u);
    EXPECT_TRUE(m.limitReached());
    const auto e = drain(q);
    ASSERT_EQ(e.size(), 2u);
    EXPECT_EQ(e[0].t, 1);
    EXPECT_EQ(e[1].t, 2);
    EXPECT_EQ(m.addPacket(s.data(), 4, 2, q), 0u);
}

TEST(LiveEdges, AFullQueueDropsWholePacketsCountsThemAndResyncs) {
    LiveEdgeQueue q(2, 1 << 20);
    LiveEdgeMaker m;
    m.select({0});
    const std::vector<std::uint8_t> low(100, 0), high(100, 1);
    m.addPacket(low.data(), 100, 1, q);
    m.addPacket(low.data(), 100, 1, q);
    ASSERT_TRUE(q.full());  // the decoder took nothing yet
    m.dropPacket(high.data(), 100, 1, q);
    const LiveCounts c = q.counts();
    EXPECT_EQ(c.samples, 300u);
    EXPECT_EQ(c.dropped_samples, 100u);
    EXPECT_EQ(c.dropped_packets, 1u);
    EXPECT_EQ(drain(q).size(), 0u);
    // The line went high in the gap: the next packet starts with that edge.
    m.addPacket(high.data(), 100, 1, q);
    EXPECT_EQ(asTriples(drain(q)), (std::vector<std::array<std::uint64_t, 3>>{{300, 0, 1}}));
    EXPECT_GE(q.counts().max_lag_samples, 0u);
}

TEST(LiveEdges, AGapOfSeveralPacketsIsOneFindingOnTheBlockAfterIt) {
    LiveEdgeQueue q(1, 1 << 20);
    LiveEdgeMaker m;
    m.select({0});
    const std::vector<std::uint8_t> low(100, 0), high(100, 1);
    for (const auto& [packet, n, dropped] :
         {std::tuple{&low, 100, false}, {&high, 100, true}, {&low, 50, true}})
        dropped ? m.dropPacket(packet->data(), std::size_t(n), 1, q)
                : m.addPacket(packet->data(), std::size_t(n), 1, q);
    EdgeBlock b;
    std::atomic<bool> stop{true};
    ASSERT_TRUE(q.pop(b, &stop));
    EXPECT_TRUE(b.findings.empty());
    m.addPacket(high.data(), 100, 1, q);
    ASSERT_TRUE(q.pop(b, &stop));
    ASSERT_EQ(b.findings.size(), 1u);
    const Event& gap = b.findings[0];
    EXPECT_EQ(gap.proto, "capture");
    EXPECT_EQ(gap.type, "samples_dropped");
    // Samples 100 to 249 dropped; the lines jump to their levels at 250.
    EXPECT_EQ(gap.start, 100);
    EXPECT_EQ(gap.end, 250);
    ASSERT_NE(gap.get("samples"), nullptr);
    EXPECT_EQ(asInt(*gap.get("samples")), 150);
    EXPECT_EQ(gap.errors, std::vector<std::string>{"samples_dropped"});
    EXPECT_EQ(asTriples(b.edges), (std::vector<std::array<std::uint64_t, 3>>{{250, 0, 1}}));
    // The next gap is a finding of its own.
    m.dropPacket(low.data(), 10, 1, q);
    m.addPacket(low.data(), 10, 1, q);
    ASSERT_TRUE(q.pop(b, &stop));
    ASSERT_EQ(b.findings.size(), 1u);
    EXPECT_EQ(b.findings[0].start, 350);
    EXPECT_EQ(b.findings[0].end, 360);
}

TEST(LiveEdges, ManyChangesFillSeveralBlocks) {
    LiveEdgeQueue q(64, 1 << 22);
    LiveEdgeMaker m;
    m.select({0});
    std::vector<std::uint8_t> s(3 * kEdgeBlockSize);
    for (std::size_t i = 0; i < s.size(); ++i)
        s[i] = std::uint8_t(i & 1);
    m.addPacket(s.data(), s.size(), 1, q);
    const auto e = drain(q);
    ASSERT_EQ(e.size(), s.size() - 1);
    for (std::size_t i = 0; i < e.size(); ++i)
        ASSERT_EQ(e[i].t, Tick(i + 1));
}

TEST(LiveDevice, SpecsWithOptions) {
    const LiveSettings s = parseDeviceSpec("fx2lafw:conn=1.5");
    EXPECT_EQ(s.driver, "fx2lafw");
    ASSERT_EQ(s.options.size(), 1u);
    EXPECT_EQ(s.options[0].second, "1.5");
    const LiveSettings p = parseDeviceSpec("playback:file=C:/x:y.sr");
    ASSERT_EQ(p.options.size(), 1u);
    EXPECT_EQ(p.options[0].second, "C:/x:y.sr");
    EXPECT_THROW(parseDeviceSpec(":conn=1"), InputError);
    EXPECT_THROW(parseDeviceSpec("demo:oops"), InputError);
}

}  // namespace
}  // namespace busdecode
