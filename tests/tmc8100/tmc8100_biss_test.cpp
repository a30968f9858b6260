// The BiSS demo firmware's dialogue with the BiSS-C encoder side in the same capture: the
// encoder cable comes from the bissc decoder's own generator (MA/SLO), placed between
// each 0x80 command and its replies, and a bissc decoder in the same pass lets every
// encoder_read say whether the TMC8100's answer is what crossed the cable.
#include <gtest/gtest.h>

#include "bissc_decoder.h"
#include "bissc_generator.h"
#include "core/crc.h"
#include "core/gray.h"
#include "core/registry.h"
#include "core/session.h"
#include "scenario_expect.h"

using namespace busdecode;
using namespace busdecode::test;

namespace {

struct BissDialogue {
    Tmc8100Scenario sc;
    BisscGenerator biss{[] {
        BisscGenConfig c;
        c.bits = 13;  // the demo's 13-bit single-turn
        c.lead_ns = 0;
        return c;
    }()};
    std::vector<std::uint16_t> on_cable, reported;

    // One read: the frame on the cable carries `cable`; the TMC8100 reports `report`.
    void read(std::uint16_t cable, std::uint16_t report) {
        sc.transfer(0x80000000u, 0);
        const double frame_at = sc.now() - 2000;  // the firmware clocks right after the command
        biss.pause(frame_at - biss.nowNs());
        const auto& f = biss.addFrame({cable, 1, 1, 0, 0, 0, 0, false, -1});
        sc.pause(double(f.end) - sc.now() + 1000);
        sc.setAvail(true);
        sc.pause(2000);
        const std::uint32_t crc = bissCrc6((std::uint64_t(report) << 2) | 0b11, 15);
        sc.transfer(0, 0x10000000u | report);
        sc.transfer(0, 0x20000000u | report);  // the BiSS encoder here sends binary
        sc.transfer(0, 0x70030000u | (crc << 8) | crc);
        sc.transfer(0, 0x71000000u | 30);
        sc.pause(1000);
        sc.setAvail(false);
        sc.pause(5000);
        on_cable.push_back(cable);
        reported.push_back(report);
    }
    Waveform build() const {
        Waveform w = sc.build();
        Waveform b = biss.build();
        b.end = std::max(b.end, w.end);
        w.end = b.end;
        return mergeWaveforms(w, b);
    }
};

}  // namespace

TEST(Tmc8100Biss, EncoderReadsAgreeOrNotWithTheBisscFrame) {
    registerDecoders();
    Registry::instance().add(makeBisscFactory());
    BissDialogue d;
    d.sc.getProtocol("BISS");
    d.read(0x0A5A, 0x0A5A);
    d.read(0x1FFF, 0x1FFF);
    d.read(0x0123, 0x0124);  // the answer differs from the cable
    auto events = decodeWaveform(d.build(), {DecoderRequest{"tmc8100", {}, {{"encoder", "auto"}}},
                                             DecoderRequest{"bissc", {}, {{"bits", "13"}}}});
    auto frames = only(events, "bissc", "frame");
    ASSERT_EQ(frames.size(), 3u);
    auto reads = only(events, "tmc8100", "encoder_read");
    ASSERT_EQ(reads.size(), 3u);
    for (int k = 0; k < 3; ++k) {
        SCOPED_TRACE(k);
        EXPECT_EQ(asInt(*frames[k].get("position")), d.on_cable[k]);
        EXPECT_EQ(asInt(*reads[k].get("gray")), d.reported[k]);
        EXPECT_EQ(show(*reads[k].get("crc_ok")), "true");
        EXPECT_EQ(show(*reads[k].get("clock_edges")), "30");
        EXPECT_EQ(show(*reads[k].get("nE")), "1");
        EXPECT_EQ(show(*reads[k].get("ssi_match")), k < 2 ? "true" : "false");
        EXPECT_EQ(asInt(*reads[k].get("encoder_st")), d.on_cable[k]);
        // The BiSS encoder sends binary, so the firmware's "Gray decode" check fails
        // unless the value happens to be its own Gray decode.
        std::vector<std::string> errs;
        if (grayToBinary(d.reported[k]) != d.reported[k]) errs.push_back("inconsistent");
        if (k == 2) errs.push_back("ssi_mismatch");
        EXPECT_EQ(reads[k].errors, errs);
    }
    auto replies = only(events, "tmc8100", "reply");
    ASSERT_GE(replies.size(), 2u);
    EXPECT_EQ(show(*replies[1].get("meaning")), "\"raw_position\"");
    EXPECT_EQ(show(*replies[3].get("meaning")), "\"status_crc\"");
}

TEST(Tmc8100Biss, GeneratorBissDemoEveryEncoderReadExact) {
    // The scenario generator's own BiSS-C side (docs/protocols.md §4.2 slot layout), decoded by
    // bissc in the same pass.
    registerDecoders();
    Registry::instance().add(makeBisscFactory());
    Tmc8100Scenario sc;
    sc.getProtocol("BISS");
    std::vector<Tmc8100Scenario::BissRead> reads(4);
    reads[0].position = 0x0A5A;
    reads[0].nw = 0;
    reads[1].position = 0x1FFF;
    reads[2].position = 0x0100;
    reads[2].corrupt_crc = true;
    reads[3].position = 0x0101;
    reads[3].reported_raw = 0x0100;
    for (const auto& r : reads) {
        sc.readEncoderBiss(r);
        sc.pause(25000);
    }
    auto events = decodeWaveform(sc.build(), {DecoderRequest{"tmc8100", {}, {}},
                                              DecoderRequest{"bissc", {}, {{"bits", "13"}}}});
    auto frames = only(events, "bissc", "frame");
    ASSERT_EQ(frames.size(), 4u);
    EXPECT_EQ(show(*frames[0].get("crc_ok")), "true");
    EXPECT_EQ(show(*frames[2].get("crc_ok")), "false");
    ScenarioExpect x{sc};
    const std::uint32_t crc0 = bissCrc6((0x0A5Aull << 2) | 0b10, 15);  // V6: 0x2B
    ASSERT_EQ(crc0, 0x2Bu);
    const std::uint32_t crc1 = bissCrc6((0x1FFFull << 2) | 0b11, 15);
    const std::uint32_t crc2 = bissCrc6((0x0100ull << 2) | 0b11, 15);
    const std::uint32_t crc3 = bissCrc6((0x0101ull << 2) | 0b11, 15);
    auto biss = [&](std::size_t c, std::int64_t raw, int ne, int nw, std::uint32_t rx,
                    std::uint32_t calc, bool match, std::int64_t cable,
                    std::vector<std::string> errors) {
        return x.read(c, c + 4, raw, std::int64_t(grayToBinary(raw)), (ne << 1) | nw, true,
                      {{"nE", I(ne)},
                       {"nW", I(nw)},
                       {"crc_rx", I(rx)},
                       {"crc_calc", I(calc)},
                       {"crc_ok", Value(rx == calc)},
                       {"clock_edges", I(2 * (4 + 13 + 2 + 6 + 1))},
                       {"ssi_match", Value(match)},
                       {"encoder_st", I(cable)}},
                      std::move(errors));
    };
    const std::vector<Expected> want = {
        biss(2, 0x0A5A, 1, 0, crc0, crc0, true, 0x0A5A, {}),
        biss(7, 0x1FFF, 1, 1, crc1, crc1, true, 0x1FFF, {}),
        biss(12, 0x0100, 1, 1, crc2 ^ 1, crc2, true, 0x0100, {"crc"}),
        biss(17, 0x0100, 1, 1, crc3, crc3, false, 0x0101, {"ssi_mismatch"}),
    };
    std::vector<Event> got = only(events, "tmc8100", "encoder_read");
    expectEvents(got, "tmc8100", want);
}
