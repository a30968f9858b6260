// The read-ahead thread (capture/prefetch_reader.h) changes nothing but speed: the same
// blocks as the wrapped reader, its input error at the same point, a clean stop.
#include <gtest/gtest.h>

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

TEST(PrefetchReader, SameBlocksAsTheWrappedReader) {
    const std::string p = file("toggles.vcd", toggles(100000));
    auto plain = openCapture(p, {});
    const Read want = readAll(*plain);
    auto pre = prefetchReader(openCapture(p, {}), 2);
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
    auto pre = prefetchReader(openCapture(p, o));
    pre->select({{0, -1}, {1, -1}});
    pre->initialLevels();
    EdgeBlock b;
    std::size_t edges = 0;
    while (edges < total && pre->next(b))
        edges += b.edges.size();
    EXPECT_EQ(edges, total);
    stop = true;  // the worker, waiting for the file to grow, must notice and let go
    pre.reset();
}

}  // namespace
