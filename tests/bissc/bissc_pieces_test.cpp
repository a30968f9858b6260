// A BiSS-C capture decoded in pieces on both threads, each piece decoded ahead by a
// decoder of its own and spliced in where its state meets the one decoding in order
// (core/piece_speculation.h), must give exactly what one decoder taking every edge in
// order gives: the same events byte for byte, the same advice, the same edge count,
// whatever the traffic (faults, jitter, glitches, Hold-CDM, register accesses) and
// wherever the pieces are cut. And the splicing must really happen where it can: on
// clean traffic nearly every piece is spliced in.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <map>
#include <random>
#include <string>
#include <vector>

#include "bissc_generator.h"
#include "bissc_random_capture.h"
#include "bissc_test_util.h"
#include "capture/capture_reader.h"
#include "capture/capture_writer.h"
#include "sinks/event_format.h"
#include "support/paths.h"

namespace busdecode::test {
namespace {

class CollectJson final : public OutputSink {
public:
    void begin(const CaptureFacts& facts) override { tb_ = facts.timebase; }
    void onEvent(const Event& e, const CaptureFacts&) override {
        appendEventJson(text, e, tb_);
        text += '\n';
    }
    std::string text;

private:
    Timebase tb_;
};

struct Decoded {
    std::string events;  // one JSON line each
    std::vector<std::string> advice;
    std::uint64_t edges = 0;
    Session::PieceStats pieces;
};

enum class Way { InOrder, Pieces, PiecesAhead };

// `path` decoded on one thread (InOrder), or in pieces of `piece_bytes` without (Pieces)
// or with (PiecesAhead) the pieces decoded ahead.
Decoded decodeFile(const std::string& path, Way way, std::uint64_t piece_bytes = 0,
                   const std::map<std::string, std::string>& options = {{"bits", "26"}},
                   const std::string& ma = "MA", const std::string& sl = "SLO") {
    registerBissc();
    OpenOptions o;
    o.read_ahead = way != Way::InOrder;
    o.vcd_piece_bytes = piece_bytes;
    o.vcd_boundary_search = 1 << 16;
    auto reader = openCapture(path, o);
    DecoderRequest r;
    r.proto = "bissc";
    if (!ma.empty()) r.map = {{"ma", ma}, {"sl", sl}};  // else bound by the signals' names
    r.options = options;
    Session s({r}, *reader, path);
    s.setPieceSpeculation(way == Way::PiecesAhead);
    CollectJson json;
    s.addSink(&json);
    s.run();
    return {json.text, s.facts().advice, s.facts().edges, s.pieceStats()};
}

void expectSame(const Decoded& got, const Decoded& want, const std::string& what) {
    EXPECT_EQ(got.edges, want.edges) << what;
    EXPECT_EQ(got.advice, want.advice) << what;
    if (got.events == want.events) return;
    // The first line that differs, not two walls of text.
    std::size_t at = 0, line = 1;
    while (at < got.events.size() && at < want.events.size() && got.events[at] == want.events[at])
        if (got.events[at++] == '\n') ++line;
    const auto lineAt = [](const std::string& s, std::size_t i) {
        const std::size_t from = s.rfind('\n', i == 0 ? 0 : i - 1);
        const std::size_t b = from == std::string::npos ? 0 : from + 1;
        return s.substr(b, s.find('\n', b) - b);
    };
    ADD_FAILURE() << what << ": event " << line << " differs:\n  got  " << lineAt(got.events, at)
                  << "\n  want " << lineAt(want.events, at);
}

std::string writeCapture(const Waveform& w, const std::string& name) {
    const std::string path = tempDir() + "/" + name + ".vcd";
    writeVcd(w, path);
    return path;
}

TEST(BisscPieces, CleanTrafficIsSplicedInAndDecodesAsInOrder) {
    BisscGenerator gen(tenMhzAt100Msps());
    std::mt19937_64 rng(7);
    for (int i = 0; i < 3000; ++i) {
        BisscFrameSpec f;
        f.data = rng() & ((1ull << 26) - 1);
        gen.addFrame(f);
    }
    const std::string path = writeCapture(gen.build(), "clean");
    const Decoded want = decodeFile(path, Way::InOrder);
    ASSERT_EQ(std::count(want.events.begin(), want.events.end(), '\n'), 3000);
    for (const std::uint64_t piece : {4096, 16384, 100000}) {
        const std::string what = fmt::format("pieces of {} bytes", piece);
        const Decoded ahead = decodeFile(path, Way::PiecesAhead, piece);
        expectSame(ahead, want, what);
        expectSame(decodeFile(path, Way::Pieces, piece), want, what + " not ahead");
        // Every piece but the first comes with a decode ahead, and all but a few are
        // spliced in at their second frame: of pieces of three frames (4 KiB), half the
        // edges are not decoded again; of longer ones, nearly all.
        EXPECT_GT(ahead.pieces.pieces, 0u) << what;
        EXPECT_GE(ahead.pieces.spliced * 10, ahead.pieces.pieces * 9) << what;
        EXPECT_GE(ahead.pieces.edges_ahead * 10, want.edges * (piece < 16384 ? 5 : 8)) << what;
    }
    EXPECT_EQ(decodeFile(path, Way::Pieces, 4096).pieces.pieces, 0u);  // off means off
}

TEST(BisscPieces, AnyTrafficDecodesAsInOrder) {
    for (std::uint32_t seed = 1; seed <= 24; ++seed) {
        const std::string path = writeCapture(randomCapture(seed, 400), fmt::format("r{}", seed));
        const Decoded want = decodeFile(path, Way::InOrder);
        for (const std::uint64_t piece : {512, 3000, 20000})
            expectSame(decodeFile(path, Way::PiecesAhead, piece), want,
                       fmt::format("seed {}, pieces of {} bytes", seed, piece));
    }
}

TEST(BisscPieces, RegisterAccessesDecodeAsInOrder) {
    // Reads and writes back to back, each byte after a few busy frames, one refused, one
    // with a bad CRC: the control reassembler holds an access open across many pieces.
    std::vector<ControlItemSpec> items;
    for (int i = 0; i < 12; ++i) {
        ControlItemSpec c;
        c.kind = i % 3 == 2 ? ControlItemSpec::Kind::Write : ControlItemSpec::Kind::Read;
        c.id = i % 8;
        c.address = 0x40 + i;
        c.data = {std::uint8_t(0x11 * i), std::uint8_t(0x5A ^ i)};
        c.busy = {i % 3, 0};
        c.refuse = i == 4;
        c.corrupt_data_crc = i == 7;
        c.idle_before = 14 + i % 5;
        items.push_back(c);
    }
    const ControlSequence seq = buildControlSequence(items);
    BisscGenerator gen(tenMhzAt100Msps());
    for (std::size_t i = 0; i < seq.cdm.size(); ++i) {
        BisscFrameSpec f;
        f.data = 0x2AAAAAA ^ i;
        f.cdm = seq.cdm[i];
        f.cds = seq.cds[i];
        gen.addFrame(f);
    }
    const std::string path = writeCapture(gen.build(), "registers");
    const Decoded want = decodeFile(path, Way::InOrder);
    ASSERT_NE(want.events.find("\"type\":\"register\""), std::string::npos);
    for (const std::uint64_t piece : {700, 4096, 30000}) {
        const Decoded ahead = decodeFile(path, Way::PiecesAhead, piece);
        expectSame(ahead, want, fmt::format("pieces of {} bytes", piece));
        // Between the accesses, in pieces of a few frames or more.
        if (piece >= 4096) {
            EXPECT_GT(ahead.pieces.spliced, 0u) << piece;
        }
    }
}

TEST(BisscPieces, RealCapturesDecodeAsInOrder) {
    // The Renishaw RESOLUTE behind an iC-Haus MB5U (bissc_real_capture_test.cpp), its
    // sigrok VCD export with only the clock in it (every frame without an ACK), and the
    // committed examples.
    const std::string renishaw = realCaptures() + "/biss-renishaw/";
    struct File {
        std::string path, ma, sl;
        std::map<std::string, std::string> options;
    };
    const std::vector<File> files = {
        {renishaw + "vcd/mb5u_10mhz.vcd", "", "", {{"bits", "32"}}},
        {renishaw + "vcd/mb5u_5mhz.vcd", "", "", {{"bits", "32"}}},
        {renishaw + "vcd/mb5u_250khz.vcd", "D1", "D3", {{"bits", "32"}}},  // unnamed probes
        {renishaw + "sigrok-vcd/renishaw_biss_10MHz.vcd", "SLO", "MA", {{"bits", "32"}}},
        {sourceDir() + "/captures/bissc_errors.vcd", "MA", "SLO", {{"bits", "26"}}},
        {sourceDir() + "/captures/bissc_1mhz_26bit.vcd", "MA", "SLO", {{"bits", "26"}}},
    };
    // The MB5U files are read in order whatever the pieces (the reader falls back), and
    // most of the examples' frames carry register accesses, where no splice point is: a
    // few pieces are spliced in, and those must be.
    std::uint64_t spliced = 0;
    for (const File& f : files) {
        const Decoded want = decodeFile(f.path, Way::InOrder, 0, f.options, f.ma, f.sl);
        ASSERT_FALSE(want.events.empty()) << f.path;
        for (const std::uint64_t piece : {64, 300, 2048, 8192}) {
            const Decoded ahead =
                decodeFile(f.path, Way::PiecesAhead, piece, f.options, f.ma, f.sl);
            expectSame(ahead, want, fmt::format("{} in pieces of {} bytes", f.path, piece));
            spliced += ahead.pieces.spliced;
        }
    }
    EXPECT_GT(spliced, 0u);
}

}  // namespace
}  // namespace busdecode::test
