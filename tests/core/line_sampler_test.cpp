// LineSampler against a plain model of what it promises: samples resolved in time order
// with the level the line had just before each, cancelled ones gone, resolved ones still
// to pop, and empty() exactly when nothing is ready or pending (BiSS-C's per-edge fast
// paths ask empty() instead of both).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <deque>
#include <random>

#include "core/line_sampler.h"

using namespace busdecode;

namespace {

struct ModelSample {
    double t;
    std::uint32_t tag;
    bool level;
    bool resolved;
};

// The obvious implementation: a queue, every sample marked resolved or not.
class ModelSampler {
public:
    void reset(bool level) {
        level_ = level;
        q_.clear();
    }
    void schedule(double t, std::uint32_t tag) { q_.push_back({t, tag, false, false}); }
    void cancelAll() {
        while (!q_.empty() && !q_.back().resolved)
            q_.pop_back();
    }
    void lineEdge(Tick t, bool level) {
        resolveBefore(double(t));
        level_ = level;
    }
    void advanceTo(Tick t) { resolveBefore(double(t)); }
    void flush() { resolveBefore(1e300); }
    bool ready() const { return !q_.empty() && q_.front().resolved; }
    std::size_t pending() const {
        std::size_t n = 0;
        for (const auto& s : q_)
            n += !s.resolved;
        return n;
    }
    ModelSample pop() {
        ModelSample s = q_.front();
        q_.pop_front();
        return s;
    }

private:
    void resolveBefore(double t) {
        for (auto& s : q_)
            if (!s.resolved && s.t < t) {
                s.resolved = true;
                s.level = level_;
            }
    }
    bool level_ = true;
    std::deque<ModelSample> q_;
};

void expectSameState(const LineSampler& s, const ModelSampler& m, int step) {
    ASSERT_EQ(s.ready(), m.ready()) << "step " << step;
    ASSERT_EQ(s.pending(), m.pending()) << "step " << step;
    ASSERT_EQ(s.empty(), !m.ready() && m.pending() == 0) << "step " << step;
}

// Pops one sample from each (the model has one ready): the same sample, the same level.
void expectSamePop(LineSampler& s, ModelSampler& m, int run, int step) {
    ASSERT_TRUE(s.ready()) << "run " << run << " step " << step;
    const auto a = s.pop();
    const auto b = m.pop();
    ASSERT_EQ(a.tag, b.tag) << "run " << run << " step " << step;
    ASSERT_EQ(a.t, b.t);
    ASSERT_EQ(a.level, b.level);
}

}  // namespace

TEST(LineSampler, SamplesBeforeAnEdgeSeeTheOldLevel) {
    LineSampler s;
    s.reset(false);
    s.schedule(10.0, 1);
    s.schedule(20.0, 2);
    s.lineEdge(20, true);  // 20 is not before 20: the second sample sees the new level
    ASSERT_TRUE(s.ready());
    EXPECT_EQ(s.pending(), 1u);
    const auto a = s.pop();
    EXPECT_EQ(a.tag, 1u);
    EXPECT_FALSE(a.level);
    EXPECT_FALSE(s.ready());
    s.advanceTo(21);
    const auto b = s.pop();
    EXPECT_EQ(b.tag, 2u);
    EXPECT_TRUE(b.level);
    EXPECT_TRUE(s.empty());
}

TEST(LineSampler, CancelKeepsResolvedSamplesAndEmptiesOtherwise) {
    LineSampler s;
    s.reset(true);
    s.schedule(5.0, 1);
    s.schedule(50.0, 2);
    s.advanceTo(10);
    s.cancelAll();  // sample 1 is resolved: it stays, sample 2 goes
    EXPECT_FALSE(s.empty());
    EXPECT_TRUE(s.ready());
    EXPECT_EQ(s.pending(), 0u);
    EXPECT_EQ(s.pop().tag, 1u);
    EXPECT_TRUE(s.empty());

    s.schedule(60.0, 3);
    EXPECT_FALSE(s.empty());
    s.cancelAll();  // nothing resolved: empty again, at once
    EXPECT_TRUE(s.empty());
    EXPECT_FALSE(s.ready());
    EXPECT_EQ(s.pending(), 0u);

    // Cancelled after a resolved sample was popped: nothing left to pop or resolve.
    s.schedule(70.0, 4);
    s.schedule(80.0, 5);
    s.schedule(90.0, 6);
    s.advanceTo(75);
    EXPECT_EQ(s.pop().tag, 4u);
    EXPECT_FALSE(s.empty());
    s.cancelAll();
    EXPECT_FALSE(s.ready());
    EXPECT_EQ(s.pending(), 0u);
    EXPECT_TRUE(s.empty());
}

TEST(LineSampler, EmptyOnlyWhenNothingIsReadyOrPendingWhateverTheOrder) {
    // Random sequences of every operation, checked step by step against the model;
    // long runs of scheduled samples pass the compaction threshold too.
    std::mt19937 rng(20261124);
    for (int run = 0; run < 200; ++run) {
        LineSampler s;
        ModelSampler m;
        const bool level0 = rng() & 1;
        s.reset(level0);
        m.reset(level0);
        double next_t = 0;  // schedule times never decrease
        Tick line_t = 0;    // nor do line edges and advances
        std::uint32_t tag = 0;
        for (int step = 0; step < 400; ++step) {
            switch (rng() % 8) {
                case 0:
                case 1:
                case 2: {
                    next_t += double(rng() % 7) * 0.5;
                    s.schedule(next_t, tag);
                    m.schedule(next_t, tag);
                    ++tag;
                    break;
                }
                case 3: {
                    line_t = std::max<Tick>(line_t, Tick(next_t) - 3) + Tick(rng() % 4);
                    const bool level = rng() & 1;
                    s.lineEdge(line_t, level);
                    m.lineEdge(line_t, level);
                    break;
                }
                case 4:
                    line_t += Tick(rng() % 4);
                    s.advanceTo(line_t);
                    m.advanceTo(line_t);
                    break;
                case 5:
                    if (rng() % 4 == 0) {
                        s.cancelAll();
                        m.cancelAll();
                    }
                    break;
                default:
                    while (m.ready() && (rng() & 1))
                        ASSERT_NO_FATAL_FAILURE(expectSamePop(s, m, run, step));
                    break;
            }
            expectSameState(s, m, step);
        }
        s.flush();
        m.flush();
        while (m.ready())
            ASSERT_NO_FATAL_FAILURE(expectSamePop(s, m, run, -1));
        EXPECT_TRUE(s.empty());
    }
}

TEST(LineSampler, CompactedBufferStaysConsistent) {
    // More than kCompactAt samples resolved and popped while later ones wait: the
    // buffer is compacted, and the waiting samples come out as scheduled.
    LineSampler s;
    s.reset(false);
    for (std::uint32_t i = 0; i < 5000; ++i)
        s.schedule(double(i), i);
    s.schedule(10000.0, 99999);
    s.advanceTo(5000);
    for (std::uint32_t i = 0; i < 5000; ++i) {
        ASSERT_TRUE(s.ready());
        ASSERT_EQ(s.pop().tag, i);
    }
    EXPECT_FALSE(s.ready());
    EXPECT_EQ(s.pending(), 1u);
    EXPECT_FALSE(s.empty());
    s.lineEdge(20000, true);
    const auto last = s.pop();
    EXPECT_EQ(last.tag, 99999u);
    EXPECT_FALSE(last.level);
    EXPECT_TRUE(s.empty());
}
