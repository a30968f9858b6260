// The read-ahead thread (capture/prefetch_reader.h) changes nothing but speed: the same
// blocks as the wrapped reader, its input error at the same point, a clean stop.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <utility>

#include "capture/prefetch_reader.h"
#include "core/options.h"
#include "support/paths.h"

using namespace busdecode;

namespace {

// A VCD with `n` toggles on two lines; `tail` is appended after them.
std::string toggles(int n, const std::string& tail = "") {
    std::string v =
        "$timescale 1 ns $end\n$var wire 1 ! a $end\n$var wire 1 \" b $end\n$enddefinitions $end\n"
        "#0 0! 0\"\n";
    for (int i = 1; i <= n; ++i)
        v += "#" + std::to_string(i * 10) + " " + std::to_string(i % 2) + (i % 3 ? "!" : "\"") +
             "\n";
    return v + tail;
}

std::string file(const std::string& name, const std::string& text) {
    const std::string p = test::tempDir() + "/" + name;
    test::writeFile(p, text);
    return p;
}

struct Read {
    std::vector<std::vector<Edge>> blocks;
    std::vector<Tick> known;
    std::string error;
    Tick end = 0;
};

Read readAll(CaptureReader& r) {
    Read out;
    r.select({{0, -1}, {1, -1}});
    r.initialLevels();
    EdgeBlock b;
    try {
        while (r.next(b)) {
            out.blocks.push_back(b.edges);
            out.known.push_back(b.known_until);
        }
        out.end = r.endTick();
    } catch (const InputError& e) {
        out.error = e.what();
    }
    return out;
}

bool sameEdges(const std::vector<Edge>& a, const std::vector<Edge>& b) {
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i)
        if (a[i].t != b[i].t || a[i].line != b[i].line || a[i].level != b[i].level) return false;
    return true;
}

// Follows `p` (not growing) through the read-ahead until every edge of it has come out,
// then stops: the worker, waiting for the file to grow, must notice and let go.
void followToTheEnd(const std::string& p, int batch) {
    std::size_t total = 0;
    {
        auto plain = openCapture(p, {});
        for (const auto& blk : readAll(*plain).blocks)
            total += blk.size();
    }
    std::atomic<bool> stop{false};
    OpenOptions o;
    o.follow = true;
    o.stop = &stop;
    auto pre = prefetchReader(openCapture(p, o), 32, batch);
    pre->select({{0, -1}, {1, -1}});
    pre->initialLevels();
    EdgeBlock b;
    std::size_t edges = 0;
    while (edges < total && pre->next(b))
        edges += b.edges.size();
    EXPECT_EQ(edges, total);
    stop = true;
    pre.reset();
}

TEST(PrefetchReader, SameBlocksAsTheWrappedReader) {
    const std::string p = file("toggles.vcd", toggles(100000));
    auto plain = openCapture(p, {});
    const Read want = readAll(*plain);
    for (const auto& [ahead, batch] : {std::pair{2, 1}, {2, 4}, {32, 4}, {3, 2}}) {
        SCOPED_TRACE(::testing::Message() << "ahead " << ahead << " batch " << batch);
        auto pre = prefetchReader(openCapture(p, {}), ahead, batch);
        const Read got = readAll(*pre);
        ASSERT_GT(want.blocks.size(), 3u);
        ASSERT_EQ(got.blocks.size(), want.blocks.size());
        for (std::size_t i = 0; i < want.blocks.size(); ++i) {
            EXPECT_TRUE(sameEdges(got.blocks[i], want.blocks[i])) << "block " << i;
            EXPECT_EQ(got.known[i], want.known[i]) << "block " << i;
        }
        EXPECT_EQ(got.end, want.end);
        EXPECT_EQ(pre->bytesRead(), plain->bytesRead());
    }
}

// A followed file that stops growing: every edge read so far is handed on while the
// reader waits for more, with batch 1 and with a batch (the last block read is short of
// full, which ends the decoder's wait for more blocks).
TEST(PrefetchReader, AFollowedFileIsHandedOnWhileItWaits) {
    const std::string p = file("grow.vcd", toggles(40000));
    for (int batch : {1, 8}) {
        SCOPED_TRACE(batch);
        followToTheEnd(p, batch);
    }
}

// A reader that hands out the blocks it is given, then waits (as a live input waits for
// data) until released, or 10 s at most.
class StallingReader : public CaptureReader {
public:
    explicit StallingReader(std::vector<std::size_t> sizes) : sizes_(std::move(sizes)) {}
    const std::vector<SignalInfo>& signals() const override { return signals_; }
    Timebase timebase() const override { return {1, 1'000'000}; }
    std::string formatName() const override { return "test"; }
    void select(const std::vector<LineRef>&) override {}
    std::vector<std::uint8_t> initialLevels() override { return {0}; }
    Tick startTick() const override { return 0; }
    bool next(EdgeBlock& block) override {
        block.clear();
        if (given_ < sizes_.size()) {
            for (std::size_t i = 0; i < sizes_[given_]; ++i, ++t_)
                block.edges.push_back({t_, 0, std::uint8_t(t_ & 1)});
            block.known_until = t_ - 1;
            ++given_;
            return true;
        }
        std::unique_lock<std::mutex> lock(m_);
        released_by_timeout_ = !cv_.wait_for(lock, std::chrono::seconds(10), [&] { return go_; });
        return false;
    }
    Tick endTick() const override { return t_; }
    void release() {
        {
            std::lock_guard<std::mutex> lock(m_);
            go_ = true;
        }
        cv_.notify_all();
    }
    bool releasedByTimeout() {
        std::lock_guard<std::mutex> lock(m_);
        return released_by_timeout_;
    }

private:
    std::vector<SignalInfo> signals_{{"a", "a", 1}};
    std::vector<std::size_t> sizes_;
    std::size_t given_ = 0;
    Tick t_ = 1;
    std::mutex m_;
    std::condition_variable cv_;
    bool go_ = false, released_by_timeout_ = false;
};

// With a batch, a block short of full ends the decoder's wait at once: here a full block
// and a short one, then the reader stalls. Both must come out while it stalls.
TEST(PrefetchReader, ABlockShortOfFullIsNotHeldForTheBatch) {
    for (std::size_t last : {std::size_t(10), kEdgeBlockSize / 2 - 1}) {
        auto inner =
            std::make_unique<StallingReader>(std::vector<std::size_t>{kEdgeBlockSize, last});
        StallingReader* stalling = inner.get();
        auto pre = prefetchReader(std::move(inner), 32, 8);
        pre->select({{0, -1}});
        pre->initialLevels();
        EdgeBlock b;
        ASSERT_TRUE(pre->next(b));
        EXPECT_EQ(b.edges.size(), kEdgeBlockSize);
        ASSERT_TRUE(pre->next(b));
        EXPECT_EQ(b.edges.size(), last);
        stalling->release();
        EXPECT_FALSE(pre->next(b));
        EXPECT_FALSE(stalling->releasedByTimeout()) << "the short block waited for the batch";
    }
}

TEST(PrefetchReader, InputErrorAfterTheBlocksBeforeIt) {
    const std::string p = file("backwards.vcd", toggles(60000, "#5 1!\n"));
    auto plain = openCapture(p, {});
    const Read want = readAll(*plain);
    ASSERT_FALSE(want.error.empty());
    auto pre = prefetchReader(openCapture(p, {}));
    const Read got = readAll(*pre);
    EXPECT_EQ(got.error, want.error);
    ASSERT_EQ(got.blocks.size(), want.blocks.size());
    for (std::size_t i = 0; i < want.blocks.size(); ++i)
        EXPECT_TRUE(sameEdges(got.blocks[i], want.blocks[i]));
}

TEST(PrefetchReader, DestroyedMidwayAndWhileFollowing) {
    const std::string p = file("many.vcd", toggles(200000));
    {
        auto pre = prefetchReader(openCapture(p, {}), 1);
        pre->select({{0, -1}, {1, -1}});
        pre->initialLevels();
        EdgeBlock b;
        ASSERT_TRUE(pre->next(b));  // the worker is now blocked on a full queue
    }
    followToTheEnd(p, 1);
}

}  // namespace
