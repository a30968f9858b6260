// Live inputs: following a growing file, pipes and standard input. The outcomes do not
// depend on timing: a writer thread feeds the input, the reader must deliver exactly
// what was written, never a half-written line, and return promptly with what it has.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <unistd.h>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <thread>

#include "capture/capture_writer.h"
#include "capture_util.h"
#include "core/waveform.h"

namespace busdecode::test {
namespace {

const std::string kHeader =
    "$timescale 1ns $end\n$var wire 1 ! a $end\n$var wire 1 \" b $end\n$enddefinitions $end\n";

void append(const std::string& path, const std::string& text) {
    FILE* f = std::fopen(path.c_str(), "a");
    ASSERT_NE(f, nullptr);
    std::fwrite(text.data(), 1, text.size(), f);
    std::fclose(f);
}

// Calls next() until `want` edges arrived (or a generous safety limit passes).
std::vector<Edge> waitEdges(CaptureReader& r, std::size_t want, EdgeBlock* last_block = nullptr) {
    std::vector<Edge> got;
    EdgeBlock b;
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
    while (got.size() < want && std::chrono::steady_clock::now() < deadline) {
        if (!r.next(b)) break;
        got.insert(got.end(), b.edges.begin(), b.edges.end());
        if (last_block && !b.edges.empty()) *last_block = b;
    }
    return got;
}

TEST(Follow, GrowingVcdDeliversPromptlyAndNeverHalfLines) {
    const std::string p = tempCapture("follow.vcd", kHeader + "#0 0! 0\"\n");
    std::atomic<bool> stop{false};
    OpenOptions o;
    o.follow = true;
    o.stop = &stop;
    auto r = openCapture(p, o);
    r->select({{0, -1}, {1, -1}});
    EXPECT_EQ(r->initialLevels(), (std::vector<std::uint8_t>{0, 0}));  // does not wait for more
    EXPECT_EQ(r->startTick(), 0);

    // Three complete lines: next() hands them over at once, not after a full block.
    append(p, "#10 1!\n#20 1\"\n#30 0!\n");
    EdgeBlock last;
    auto got = waitEdges(*r, 3, &last);
    EXPECT_EQ(got, (std::vector<Edge>{{10, 0, 1}, {20, 1, 1}, {30, 0, 0}}));
    EXPECT_EQ(last.known_until, 30);

    // A line written in two pieces is only read once complete.
    append(p, "#40 1");
    EdgeBlock b;
    ASSERT_TRUE(r->next(b));  // nothing complete: an empty block after a short wait
    EXPECT_TRUE(b.edges.empty());
    append(p, "! 0\"\n");
    got = waitEdges(*r, 2);
    EXPECT_EQ(got, (std::vector<Edge>{{40, 0, 1}, {40, 1, 0}}));

    stop = true;
    EXPECT_FALSE(r->next(b));
}

TEST(Follow, WriterThreadAndStopFlag) {
    const std::string p = tempCapture("follow2.vcd", kHeader + "#0 0! 0\"\n");
    std::atomic<bool> stop{false};
    OpenOptions o;
    o.follow = true;
    o.stop = &stop;
    auto r = openCapture(p, o);
    r->select({{0, -1}});
    r->initialLevels();
    std::thread writer([&] {
        for (int i = 1; i <= 200; ++i) {
            append(p, "#" + std::to_string(i * 10) + " " + std::to_string(i & 1) + "!\n");
            if (i % 50 == 0) std::this_thread::sleep_for(std::chrono::milliseconds(10));
        }
    });
    auto got = waitEdges(*r, 200);
    writer.join();
    ASSERT_EQ(got.size(), 200u);
    for (int i = 0; i < 200; ++i)
        EXPECT_EQ(got[i].t, (i + 1) * 10);
    stop = true;
    EdgeBlock b;
    EXPECT_FALSE(r->next(b));
}

// `p` followed until its first edge came.
std::unique_ptr<CaptureReader> followedPastItsFirstEdge(const std::string& p) {
    OpenOptions o;
    o.follow = true;
    auto r = openCapture(p, o);
    r->select({{0, -1}});
    r->initialLevels();
    EXPECT_EQ(waitEdges(*r, 1).size(), 1u);
    return r;
}

// The error reading on from `r` ends in ("" when none came).
std::string errorReadingOn(CaptureReader& r) {
    EdgeBlock b;
    try {
        for (int i = 0; i < 100; ++i)
            r.next(b);
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

TEST(Follow, TruncatedOrDeletedFileIsAnError) {
    for (bool remove : {false, true}) {
        const std::string p = tempCapture("trunc.vcd", kHeader + "#0 0!\n#5 1!\n");
        auto r = followedPastItsFirstEdge(p);
        if (remove) {
            std::remove(p.c_str());
        } else {
            ASSERT_EQ(truncate(p.c_str(), 10), 0);
        }
        EXPECT_EQ(errorReadingOn(*r),
                  p + (remove ? ": deleted while following" : ": truncated while following"));
    }
}

TEST(Follow, AFileReplacedByRenameSaysSoNotDeleted) {
    const std::string p = tempCapture("replaced.vcd", kHeader + "#0 0!\n#5 1!\n");
    auto r = followedPastItsFirstEdge(p);
    const std::string fresh = tempCapture("replaced.new", kHeader + "#0 1!\n");
    ASSERT_EQ(std::rename(fresh.c_str(), p.c_str()), 0);
    const std::string error = errorReadingOn(*r);
    EXPECT_EQ(error.rfind(p + ": replaced by another file while following", 0), 0u) << error;
}

TEST(Follow, GrowingSaleaeCsv) {
    const std::string p = tempCapture("follow.csv", "Time [s],A\n0.000000000,0\n");
    std::atomic<bool> stop{false};
    OpenOptions o;
    o.follow = true;
    o.stop = &stop;
    auto r = openCapture(p, o);
    r->select({{0, -1}});
    EXPECT_EQ(r->initialLevels(), (std::vector<std::uint8_t>{0}));
    append(p, "0.000000100,1\n0.000000200,0\n");
    EXPECT_EQ(waitEdges(*r, 2), (std::vector<Edge>{{100, 0, 1}, {200, 0, 0}}));
    stop = true;
    EdgeBlock b;
    EXPECT_FALSE(r->next(b));
}

// A pipe (as /dev/fd/N) is read as a stream to its end, in pieces.
TEST(Stdin, PipeIsReadToTheEnd) {
    int fds[2];
    ASSERT_EQ(pipe(fds), 0);
    std::string text = kHeader + "#0 0! 0\"\n";
    for (int i = 1; i <= 30000; ++i)
        text += "#" + std::to_string(i) + " " + std::to_string(i & 1) + "!\n";
    std::thread writer([&] {
        std::size_t off = 0;
        while (off < text.size()) {  // uneven pieces, lines cut anywhere
            std::size_t n = std::min<std::size_t>(4093, text.size() - off);
            ssize_t w = write(fds[1], text.data() + off, n);
            if (w <= 0) break;
            off += std::size_t(w);
        }
        close(fds[1]);
    });
    auto c = collectFile("/dev/fd/" + std::to_string(fds[0]));
    writer.join();
    close(fds[0]);
    EXPECT_EQ(c.edges.size(), 30000u);
    EXPECT_EQ(c.end, 30000);
}

// "-" is standard input: a VCD and a .sr (copied to a seekable temporary file).
TEST(Stdin, DashReadsStandardInput) {
    Waveform w;
    {
        WaveBuilder b(Timebase::fromSampleRate(1'000'000), {"A", "B"}, {0, 1});
        b.set(0, 3, true);
        b.set(1, 5, false);
        w = b.build(9);
    }
    const std::string vcd = tempDir() + "/stdin.vcd";
    writeVcd(w, vcd);
    const std::string sr = realCaptures() + "/sigrok-dumps/uart/rxtx_overlapped/rxtx_overlapped.sr";
    const auto want_sr = collectFile(sr, {"RX", "TX"});
    for (const std::string& src : {vcd, sr}) {
        int saved = dup(0);
        int fds[2];
        ASSERT_EQ(pipe(fds), 0);
        const std::string data = readFile(src);
        std::thread writer([&] {
            std::size_t off = 0;
            while (off < data.size()) {
                ssize_t n = write(fds[1], data.data() + off, data.size() - off);
                if (n <= 0) break;
                off += std::size_t(n);
            }
            close(fds[1]);
        });
        dup2(fds[0], 0);
        close(fds[0]);
        Collected c;
        if (src == vcd)
            c = collectFile("-", {"A", "B"});
        else
            c = collectFile("-", {"RX", "TX"});
        writer.join();
        dup2(saved, 0);
        close(saved);
        if (src == vcd) {
            EXPECT_EQ(c.format, "vcd");
            EXPECT_EQ(c.edges, w.edges);
        } else {
            EXPECT_EQ(c.format, "sigrok-sr");
            EXPECT_EQ(c.edges, want_sr.edges);
            EXPECT_GT(c.edges.size(), 10u);
        }
    }
}

}  // namespace
}  // namespace busdecode::test
