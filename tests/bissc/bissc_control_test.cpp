// BiSS-C control communication: the complete register accesses of docs/protocols.md §4.4
// (V20-V24) fed bit by bit into the reassembler, the CRC4 vectors of §4.3, and
// generated captures carrying reads, writes, busy repeats, refusals, bad CRCs and
// commands over CDM/CDS, decoded end to end.
#include <gtest/gtest.h>

#include <random>

#include "bissc_control.h"
#include "bissc_generator.h"
#include "bissc_test_util.h"
#include "core/crc.h"

using namespace busdecode;
using namespace busdecode::test;

namespace {

// Feeds per-frame bit strings (CDM and CDS of frame f at index f) after a 14-zero
// preamble; missing bits are idle zeros. Frame f occupies ticks [100 f, 100 f + 90].
std::vector<Event> reassemble(const std::string& cdm, const std::string& cds, int preamble = 14) {
    std::vector<Event> out;
    BisscControlReassembler r([&](Event&& e) { out.push_back(std::move(e)); });
    const int n = int(std::max(cdm.size(), cds.size())) + 20;
    for (int f = -preamble; f < n; ++f) {
        ControlBits b;
        b.start = Tick(100) * f;
        b.end = b.start + 90;
        b.cdm = (f >= 0 && f < int(cdm.size())) ? cdm[f] - '0' : 0;
        b.cds = (f >= 0 && f < int(cds.size())) ? cds[f] - '0' : 0;
        r.push(b);
    }
    r.finish();
    return out;
}

bool boolField(const Event& e, const char* key) {
    return std::get<bool>(*e.get(key));
}

}  // namespace

TEST(BisscCrc4, ControlVectors) {
    // docs/protocols.md §4.3 (the AN22 captured ones are also in core_tests).
    EXPECT_EQ(bissCrc4((1u << 10) | 0x00, 11), 0b0110u);
    EXPECT_EQ(bissCrc4((1u << 10) | 0x7E, 11), 0b1111u);
    EXPECT_EQ(bissCrc4((1u << 10) | 0x42, 11), 0b0111u);
    EXPECT_EQ(bissCrc4((1u << 10) | 0x7F, 11), 0b1100u);
    EXPECT_EQ(bissCrc4((1u << 10) | (1u << 7) | 0x40, 11), 0b1111u);
    EXPECT_EQ(bissCrc4((1u << 10) | (7u << 7) | 0x48, 11), 0b0110u);
    EXPECT_EQ(bissCrc4(0x48, 8), 0b0011u);
    EXPECT_EQ(bissCrc4(0x44, 8), 0b0100u);
    EXPECT_EQ(bissCrc4(0x00, 8), 0b1111u);
    EXPECT_EQ(bissCrc4(0x01, 8), 0b1100u);
    EXPECT_EQ(bissCrc4(0x12, 8), 0b1100u);
    EXPECT_EQ(bissCrc4(0xA5, 8), 0b0100u);
    EXPECT_EQ(bissCrc4(0xFF, 8), 0b1011u);
    EXPECT_EQ(bissCrc4(0x69, 8), 0b1010u);
    EXPECT_EQ(bissCrc4(0x43, 8), 0b1101u);
    // Commands: CTS = 0, IDS0..7, CMD1..0.
    EXPECT_EQ(bissCrc4(0b0'00000000'00, 11), 0b1111u);
    EXPECT_EQ(bissCrc4(0b0'00000000'01, 11), 0b1100u);
    EXPECT_EQ(bissCrc4(0b0'10000000'11, 11), 0b0111u);
}

TEST(BisscControlVectors, V20_read_7E) {
    const auto ev =
        reassemble("11000111111011111010000000000000", "010000000000000001010001001011000");
    ASSERT_EQ(ev.size(), 1u);
    const Event& e = ev[0];
    EXPECT_EQ(e.type, "register");
    EXPECT_EQ(std::get<std::string>(*e.get("op")), "read");
    EXPECT_EQ(intField(e, "id"), 0);
    EXPECT_EQ(intField(e, "address"), 0x7E);
    EXPECT_EQ(intField(e, "data"), 0x12);
    EXPECT_TRUE(boolField(e, "crc_ok"));
    EXPECT_EQ(intField(e, "busy_frames"), 0);
    EXPECT_EQ(intField(e, "idl"), 0x80);  // "IDL:80" as AN22 shows it
    EXPECT_EQ(e.start, 0);                // frame 0 (CDM = S) ...
    EXPECT_EQ(e.end, 32 * 100 + 90);      // ... to frame 32 (slave's P)
    EXPECT_TRUE(e.errors.empty());
}

TEST(BisscControlVectors, V20_MA_levels_are_inverted_CDM) {
    // The MA level in the timeout is the inverted CDM: check the vector's own consistency.
    const std::string cdm = "11000111111011111010000000000000";
    const std::string ma = "00111000000100000101111111111111";
    ASSERT_EQ(cdm.size(), ma.size());
    for (std::size_t i = 0; i < cdm.size(); ++i)
        EXPECT_NE(cdm[i], ma[i]);
}

TEST(BisscControlVectors, V21_read_42) {
    const auto ev =
        reassemble("11000100001001111010000000000000", "010000000000000001011010010101000");
    ASSERT_EQ(ev.size(), 1u);
    EXPECT_EQ(std::get<std::string>(*ev[0].get("op")), "read");
    EXPECT_EQ(intField(ev[0], "address"), 0x42);
    EXPECT_EQ(intField(ev[0], "data"), 0xA5);
    EXPECT_TRUE(boolField(ev[0], "crc_ok"));
    EXPECT_TRUE(ev[0].errors.empty());
}

TEST(BisscControlVectors, V22_write_48) {
    const auto ev =
        reassemble("11000100100010100111010010101000", "010000000000000000111010010101000");
    ASSERT_EQ(ev.size(), 1u);
    EXPECT_EQ(std::get<std::string>(*ev[0].get("op")), "write");
    EXPECT_EQ(intField(ev[0], "address"), 0x48);
    EXPECT_EQ(intField(ev[0], "data"), 0xA5);
    EXPECT_EQ(intField(ev[0], "echo"), 0xA5);
    EXPECT_TRUE(boolField(ev[0], "crc_ok"));
    EXPECT_TRUE(ev[0].errors.empty());
}

TEST(BisscControlVectors, V23_read_with_two_busy_frames) {
    const auto ev =
        reassemble("1100010000100111101110000000000000", "01000000000000000100011010010101000");
    ASSERT_EQ(ev.size(), 1u);
    EXPECT_EQ(intField(ev[0], "address"), 0x42);
    EXPECT_EQ(intField(ev[0], "data"), 0xA5);
    EXPECT_EQ(intField(ev[0], "busy_frames"), 2);
    EXPECT_TRUE(boolField(ev[0], "crc_ok"));
    EXPECT_EQ(ev[0].end, 34 * 100 + 90);
    EXPECT_TRUE(ev[0].errors.empty());
}

TEST(BisscControlVectors, V24_sequential_read_like_the_iC_MHM_capture) {
    // Sequential read from ID0 ADR 0x00 of the bytes in the AN22 capture, with
    // "P, Busy, S" between bytes (one busy frame each), built from the layout rules.
    const std::vector<std::uint8_t> bytes = {0x48, 0x44, 0x00, 0x78, 0x80, 0x00, 0x00, 0x00,
                                             0xCF, 0x80, 0x00, 0x00, 0x23, 0x00, 0x00, 0x00};
    ControlItemSpec rd;
    rd.address = 0x00;
    rd.data = bytes;
    rd.busy = std::vector<int>(bytes.size(), 1);
    rd.busy[0] = 0;
    ControlItemSpec rd2;
    rd2.address = 0x10;
    rd2.data = {0x00, 0x00, 0x00, 0x8C};
    const ControlSequence seq = buildControlSequence({rd, rd2});
    std::string cdm, cds;
    for (std::size_t i = 14; i < seq.cdm.size(); ++i) {
        cdm += char('0' + seq.cdm[i]);
        cds += char('0' + seq.cds[i]);
    }
    // The header bits as AN22 decodes them: S CTS:1 ID:0 ADR:00 CRC:6 R:1 W:0 S.
    EXPECT_EQ(cdm.substr(0, 19), "1100000000000110101");
    const auto ev = reassemble(cdm, cds);
    ASSERT_EQ(ev.size(), 20u);
    for (std::size_t i = 0; i < 16; ++i) {
        SCOPED_TRACE(i);
        EXPECT_EQ(intField(ev[i], "address"), std::int64_t(i));
        EXPECT_EQ(intField(ev[i], "data"), bytes[i]);
        EXPECT_EQ(intField(ev[i], "sequence"), std::int64_t(i));
        EXPECT_EQ(intField(ev[i], "busy_frames"), i == 0 ? 0 : 1);
        EXPECT_TRUE(boolField(ev[i], "crc_ok"));
    }
    EXPECT_EQ(intField(ev[16], "address"), 0x10);
    EXPECT_EQ(intField(ev[19], "address"), 0x13);
    EXPECT_EQ(intField(ev[19], "data"), 0x8C);
    // The first data byte carries CRC 3 on CDS, as the capture shows ("D:48 CRC:3").
    EXPECT_EQ(cds.substr(20, 12), "010010000011");
}

TEST(BisscControl, NoStartWithoutPreamble) {
    // V20 with only 10 zeros before S: not a control frame start.
    const auto ev =
        reassemble("11000111111011111010000000000000", "010000000000000001010001001011000", 10);
    EXPECT_TRUE(ev.empty());
}

TEST(BisscControl, RefusedReadAndWrite) {
    ControlItemSpec rd;
    rd.address = 0x30;
    rd.data = {0x00};
    rd.refuse = true;
    ControlItemSpec wr;
    wr.kind = ControlItemSpec::Kind::Write;
    wr.address = 0x31;
    wr.data = {0x55};
    wr.refuse = true;
    const ControlSequence seq = buildControlSequence({rd, wr});
    std::string cdm, cds;
    for (std::size_t i = 14; i < seq.cdm.size(); ++i) {
        cdm += char('0' + seq.cdm[i]);
        cds += char('0' + seq.cds[i]);
    }
    const auto ev = reassemble(cdm, cds);
    ASSERT_EQ(ev.size(), 2u);
    EXPECT_TRUE(ev[0].hasError("refused"));
    EXPECT_TRUE(boolField(ev[0], "refused"));
    EXPECT_EQ(std::get<std::string>(*ev[0].get("op")), "read");
    EXPECT_TRUE(ev[1].hasError("refused"));
    EXPECT_EQ(std::get<std::string>(*ev[1].get("op")), "write");
}

TEST(BisscControl, CommandsExecutedAndCancelled) {
    ControlItemSpec c1;
    c1.kind = ControlItemSpec::Kind::Command;
    c1.ids = 0b00100001;  // IDs 0 and 5: "1000 0100" on the wire
    c1.command = 0b11;
    c1.ida = 0b00000001;
    ControlItemSpec c2 = c1;
    c2.ids = 0;  // broadcast
    c2.command = 0b01;
    c2.execute = false;
    c2.ex_gap = 7;
    const ControlSequence seq = buildControlSequence({c1, c2});
    std::string cdm, cds;
    for (std::size_t i = 14; i < seq.cdm.size(); ++i) {
        cdm += char('0' + seq.cdm[i]);
        cds += char('0' + seq.cds[i]);
    }
    EXPECT_EQ(cdm.substr(0, 12), "101000010011");
    const auto ev = reassemble(cdm, cds);
    ASSERT_EQ(ev.size(), 2u);
    EXPECT_EQ(ev[0].type, "command");
    EXPECT_EQ(intField(ev[0], "id"), 0b00100001);
    EXPECT_EQ(intField(ev[0], "command"), 3);
    EXPECT_EQ(intField(ev[0], "ida"), 1);
    EXPECT_TRUE(boolField(ev[0], "crc_ok"));
    EXPECT_TRUE(boolField(ev[0], "executed"));
    EXPECT_EQ(std::get<std::vector<std::int64_t>>(*ev[0].get("targets")),
              (std::vector<std::int64_t>{0, 5}));
    EXPECT_TRUE(ev[0].errors.empty());
    EXPECT_TRUE(boolField(ev[1], "broadcast"));
    EXPECT_FALSE(boolField(ev[1], "executed"));
    EXPECT_TRUE(ev[1].hasError("cancelled"));
}

TEST(BisscControl, CaptureEndingMidAccessReportsWhatWasSeen) {
    const auto full = std::string("11000111111011111010000000000000");
    std::vector<Event> out;
    BisscControlReassembler r([&](Event&& e) { out.push_back(std::move(e)); });
    for (int f = 0; f < 14; ++f)
        r.push({Tick(f), Tick(f), 0, 0});
    const std::string cds = "010000000000000001010001";
    for (int f = 0; f < 24; ++f)
        r.push({Tick(100 + f), Tick(100 + f), full[f] - '0', cds[f] - '0'});
    EXPECT_EQ(r.openSince(), 100);
    r.finish();
    ASSERT_EQ(out.size(), 1u);
    EXPECT_TRUE(out[0].hasError("short_frame"));
    EXPECT_EQ(intField(out[0], "address"), 0x7E);
    EXPECT_TRUE(nullField(out[0], "data"));
    EXPECT_EQ(r.openSince(), kNoTick);
}

// ---- End to end: generated captures carrying control sequences ----

struct ControlCase {
    double clock_hz;
    int bits;
    double delay_ns;
    int proc;
    bool hold;
};

class BisscControlCapture : public ::testing::TestWithParam<ControlCase> {};

// One access or command of every kind and outcome: read, write, busy, bad data CRC, bad
// header CRC, refused, abandoned, command.
std::vector<ControlItemSpec> controlItemsOfEveryKind() {
    std::vector<ControlItemSpec> items;
    ControlItemSpec rd;
    rd.address = 0x7E;
    rd.data = {0x12};
    items.push_back(rd);
    ControlItemSpec wr;
    wr.kind = ControlItemSpec::Kind::Write;
    wr.id = 2;
    wr.address = 0x48;
    wr.data = {0xA5, 0x5A};
    items.push_back(wr);
    ControlItemSpec busy;
    busy.address = 0x42;
    busy.data = {0xA5, 0x01, 0xFF};
    busy.busy = {2, 0, 5};
    items.push_back(busy);
    ControlItemSpec bad;
    bad.address = 0x10;
    bad.data = {0x33};
    bad.corrupt_data_crc = true;
    items.push_back(bad);
    ControlItemSpec badhdr;
    badhdr.kind = ControlItemSpec::Kind::Write;
    badhdr.address = 0x11;
    badhdr.data = {0x44};
    badhdr.corrupt_header_crc = true;
    items.push_back(badhdr);
    ControlItemSpec refused;
    refused.address = 0x50;
    refused.data = {0};
    refused.refuse = true;
    items.push_back(refused);
    ControlItemSpec abandoned;
    abandoned.address = 0x20;
    abandoned.data = {0x99};
    abandoned.busy = {10};
    abandoned.abandon_after_busy = 3;
    items.push_back(abandoned);
    ControlItemSpec cmd;
    cmd.kind = ControlItemSpec::Kind::Command;
    cmd.ids = 1;
    cmd.command = 2;
    cmd.ida = 1;
    items.push_back(cmd);
    return items;
}

// A frame per CDM bit of `seq`, random positions, every 37th frame's CRC bad.
BisscGenerator captureCarrying(const ControlCase& c, const ControlSequence& seq) {
    BisscGenConfig cfg;
    cfg.clock_hz = c.clock_hz;
    cfg.bits = c.bits;
    cfg.line_delay_ns = c.delay_ns;
    cfg.hold_cdm = c.hold;
    // The slave's timeout must exceed the clock phases (12.5 us at 80 kHz: use 20 us).
    cfg.timeout_ns = c.clock_hz < 100e3 ? 20000 : 13000;
    cfg.idle_ns = 2000;
    cfg.jitter_ns = 0.02e9 / c.clock_hz;
    BisscGenerator gen(cfg);
    std::mt19937_64 rng(c.bits);
    const std::uint64_t mask = (1ull << c.bits) - 1;
    for (std::size_t i = 0; i < seq.cdm.size(); ++i) {
        BisscFrameSpec f;
        f.data = rng() & mask;
        f.cdm = seq.cdm[i];
        f.cds = seq.cds[i];
        f.proc_cycles = c.proc;
        f.corrupt_crc = i % 37 == 11;  // bad frame CRCs do not disturb the control bits
        gen.addFrame(f);
    }
    return gen;
}

void expectControlEvent(const Event& e, const ControlEventTruth& t, const BisscGenerator& gen) {
    EXPECT_EQ(e.type, t.type);
    EXPECT_EQ(e.start, gen.frames()[t.first_frame].start);
    EXPECT_EQ(e.end, gen.frames()[t.last_frame].end);
    EXPECT_EQ(std::get<bool>(*e.get("crc_ok")), t.crc_ok);
    if (t.error.empty())
        EXPECT_TRUE(e.errors.empty());
    else
        EXPECT_TRUE(e.hasError(t.error));
    if (t.type == "register") {
        EXPECT_EQ(std::get<std::string>(*e.get("op")), t.op);
        EXPECT_EQ(intField(e, "id"), t.id);
        EXPECT_EQ(intField(e, "address"), t.address);
        EXPECT_EQ(intField(e, "busy_frames"), t.busy);
        if (t.error != "abandoned")
            EXPECT_EQ(intField(e, "data"), t.data);
        else
            EXPECT_TRUE(nullField(e, "data"));
    } else {
        EXPECT_EQ(intField(e, "id"), t.id);
        EXPECT_EQ(intField(e, "command"), t.data);
        EXPECT_EQ(std::get<bool>(*e.get("executed")), t.executed);
    }
}

TEST_P(BisscControlCapture, AllFramesAndAccessesExact) {
    const ControlCase c = GetParam();
    const ControlSequence seq = buildControlSequence(controlItemsOfEveryKind());
    const BisscGenerator gen = captureCarrying(c, seq);
    const auto events = decodeBissc(gen.build(), {{"bits", std::to_string(c.bits)}});
    const auto frames = ofType(events, "frame");
    ASSERT_EQ(frames.size(), gen.frames().size());
    for (std::size_t i = 0; i < frames.size(); ++i) {
        ASSERT_EQ(std::get<std::uint64_t>(*frames[i].get("position")), gen.frames()[i].spec.data)
            << i;
        ASSERT_EQ(intField(frames[i], "cdm"), seq.cdm[i]) << i;
        ASSERT_EQ(intField(frames[i], "cds"), seq.cds[i]) << i;
        ASSERT_EQ(frames[i].hasError("crc"), i % 37 == 11) << i;
    }

    std::vector<Event> control;
    for (const auto& e : events)
        if (e.type == "register" || e.type == "command") control.push_back(e);
    ASSERT_EQ(control.size(), seq.events.size());
    for (std::size_t i = 0; i < control.size(); ++i) {
        SCOPED_TRACE(::testing::Message() << "control event " << i << " " << control[i].summary);
        expectControlEvent(control[i], seq.events[i], gen);
    }
    // Events come out in time order.
    for (std::size_t i = 1; i < events.size(); ++i)
        EXPECT_LE(events[i - 1].start, events[i].start);
}

INSTANTIATE_TEST_SUITE_P(Rates, BisscControlCapture,
                         ::testing::Values(ControlCase{80e3, 8, 0, 0, false},
                                           ControlCase{1e6, 26, 300, 2, false},
                                           ControlCase{2e6, 32, 1500, 8, true},
                                           ControlCase{10e6, 48, 1500, 4, false},
                                           ControlCase{10e6, 13, 200, 0, true}));

// V20-V23 end to end: the vectors' CDM bits sent as MA levels in the timeouts and their
// CDS bits in generated frames (with line delay and processing time), decoded from the
// waveform.
TEST(BisscControlVectors, V20toV23ThroughGeneratedFrames) {
    struct Vec {
        const char* cdm;
        const char* cds;
        const char* op;
        int address, data, busy;
    };
    const Vec vectors[] = {
        {"11000111111011111010000000000000", "010000000000000001010001001011000", "read", 0x7E,
         0x12, 0},
        {"11000100001001111010000000000000", "010000000000000001011010010101000", "read", 0x42,
         0xA5, 0},
        {"11000100100010100111010010101000", "010000000000000000111010010101000", "write", 0x48,
         0xA5, 0},
        {"1100010000100111101110000000000000", "01000000000000000100011010010101000", "read", 0x42,
         0xA5, 2},
    };
    for (const Vec& v : vectors) {
        SCOPED_TRACE(v.cdm);
        BisscGenConfig cfg;
        cfg.clock_hz = 2e6;
        cfg.line_delay_ns = 700;
        BisscGenerator gen(cfg);
        const std::string cdm = std::string(14, '0') + v.cdm + "0";
        const std::string cds = std::string(14, '0') + v.cds;
        for (std::size_t f = 0; f < cds.size() + 2; ++f) {
            BisscFrameSpec s;
            s.data = f * 1000;
            s.proc_cycles = 3;
            s.cdm = f < cdm.size() ? cdm[f] - '0' : 0;
            s.cds = f < cds.size() ? cds[f] - '0' : 0;
            gen.addFrame(s);
        }
        const auto regs = ofType(decodeBissc(gen.build(), {}), "register");
        ASSERT_EQ(regs.size(), 1u);
        EXPECT_EQ(std::get<std::string>(*regs[0].get("op")), v.op);
        EXPECT_EQ(intField(regs[0], "address"), v.address);
        EXPECT_EQ(intField(regs[0], "data"), v.data);
        EXPECT_EQ(intField(regs[0], "busy_frames"), v.busy);
        EXPECT_TRUE(std::get<bool>(*regs[0].get("crc_ok")));
        EXPECT_EQ(regs[0].start, gen.frames()[14].start);
        EXPECT_EQ(regs[0].end, gen.frames()[cds.size() - 1].end);
        EXPECT_TRUE(regs[0].errors.empty());
    }
}

TEST(BisscControl, BrokenFrameAbandonsTheAccessAndTheNextOneDecodes) {
    ControlItemSpec rd;
    rd.address = 0x7E;
    rd.data = {0x12};
    ControlItemSpec rd2 = rd;
    rd2.address = 0x42;
    rd2.data = {0xA5};
    const ControlSequence seq = buildControlSequence({rd, rd2});
    BisscGenConfig cfg;
    cfg.clock_hz = 1e6;
    BisscGenerator gen(cfg);
    const std::size_t broken = 14 + 24;  // inside the first access's data
    for (std::size_t i = 0; i < seq.cdm.size(); ++i) {
        BisscFrameSpec f;
        f.cdm = seq.cdm[i];
        f.cds = seq.cds[i];
        if (i == broken) f.truncate_after = 10;
        gen.addFrame(f);
    }
    const auto regs = ofType(decodeBissc(gen.build(), {}), "register");
    ASSERT_EQ(regs.size(), 2u);
    EXPECT_TRUE(regs[0].hasError("abandoned"));
    EXPECT_EQ(intField(regs[0], "address"), 0x7E);
    EXPECT_TRUE(nullField(regs[0], "data"));
    EXPECT_FALSE(std::get<bool>(*regs[0].get("crc_ok")));
    EXPECT_EQ(regs[0].end, gen.frames()[broken].end);
    EXPECT_EQ(intField(regs[1], "address"), 0x42);
    EXPECT_EQ(intField(regs[1], "data"), 0xA5);
    EXPECT_TRUE(regs[1].errors.empty());
}
