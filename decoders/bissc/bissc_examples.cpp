#include "bissc_examples.h"

#include <random>
#include <utility>

#include "capture/capture_reader.h"
#include "core/session.h"
#include "sinks/event_format.h"

namespace busdecode {

namespace {

// 26-bit frames at 1 MHz over a 300 ns cable, 2 busy clocks, carrying a register read
// (ID 0, 0x7E -> 0x12, as in V20) and a sequential write with a busy slave.
BisscExample registerAccess() {
    BisscGenConfig cfg;
    cfg.clock_hz = 1e6;
    cfg.bits = 26;
    cfg.line_delay_ns = 300;
    cfg.timeout_ns = 20000;
    cfg.idle_ns = 5000;
    cfg.seed = 26;
    BisscGenerator gen(cfg);
    ControlItemSpec rd;
    rd.address = 0x7E;
    rd.data = {0x12};
    ControlItemSpec wr;
    wr.kind = ControlItemSpec::Kind::Write;
    wr.address = 0x48;
    wr.data = {0xA5, 0x5A};
    wr.busy = {0, 2};
    const ControlSequence seq = buildControlSequence({rd, wr});
    std::mt19937_64 rng(26);
    for (std::size_t i = 0; i < seq.cdm.size(); ++i) {
        BisscFrameSpec f;
        f.data = rng() & ((1ull << 26) - 1);
        f.cdm = seq.cdm[i];
        f.cds = seq.cds[i];
        f.proc_cycles = 2;
        gen.addFrame(f);
    }
    BisscExampleTruth truth{gen.frames(), seq.events};
    return {{"bissc_1mhz_26bit.vcd",
             ExampleFormat::Vcd,
             "26-bit frames at 1 MHz, 300 ns line delay, register read 0x7E and sequential write",
             {{"bissc", {}, {{"bits", "26"}}}},
             gen.build()},
            std::move(truth)};
}

// 32-bit frames at 10 MHz behind a 1.2 us cable (12 bit times), 5 busy clocks, 4 clocks
// past the stop bit; sigrok dense CSV at 100 MHz (10 samples per bit).
BisscExample longCable() {
    BisscGenConfig cfg;
    cfg.timebase = Timebase::fromSampleRate(100'000'000);
    cfg.clock_hz = 10e6;
    cfg.bits = 32;
    cfg.line_delay_ns = 1200;
    cfg.timeout_ns = 15000;
    cfg.idle_ns = 3000;
    cfg.lead_ns = 2000;
    BisscGenerator gen(cfg);
    std::mt19937_64 rng(32);
    for (int i = 0; i < 6; ++i) {
        BisscFrameSpec f;
        f.data = rng() & 0xFFFFFFFFull;
        f.proc_cycles = 5;
        f.extra_clocks = 4;
        gen.addFrame(f);
    }
    BisscExampleTruth truth{gen.frames(), {}};
    return {{"bissc_10mhz_long_cable.csv",
             ExampleFormat::SigrokCsv,
             "32-bit frames at 10 MHz with a 1.2 us line delay, sigrok CSV at 100 MHz",
             {{"bissc", {}, {{"bits", "32"}}}},
             gen.build()},
            std::move(truth)};
}

// Faults and special cases at 2 MHz, 24-bit: bad CRC, nE/nW active, a frame cut after
// 15 clocks, CDM = 1 with Hold-CDM (the next frame starts from MA low).
BisscExample faults() {
    BisscGenConfig cfg;
    cfg.clock_hz = 2e6;
    cfg.bits = 24;
    cfg.line_delay_ns = 100;
    cfg.hold_cdm = true;
    BisscGenerator gen(cfg);
    BisscFrameSpec ok;
    ok.data = 0x123456;
    gen.addFrame(ok);
    BisscFrameSpec bad = ok;
    bad.corrupt_crc = true;
    gen.addFrame(bad);
    BisscFrameSpec flags = ok;
    flags.ne = 0;
    flags.nw = 0;
    gen.addFrame(flags);
    BisscFrameSpec cut = ok;
    cut.truncate_after = 15;
    gen.addFrame(cut);
    BisscFrameSpec hold = ok;
    hold.cdm = 1;
    gen.addFrame(hold);
    gen.addFrame(ok);  // starts from MA held low
    BisscExampleTruth truth{gen.frames(), {}};
    return {{"bissc_errors.vcd",
             ExampleFormat::Vcd,
             "2 MHz 24-bit: bad CRC, nE/nW active, truncated frame, Hold-CDM",
             {{"bissc", {}, {{"bits", "24"}}}},
             gen.build()},
            std::move(truth)};
}

}  // namespace

std::vector<BisscExample> bisscExamples() {
    return {registerAccess(), longCable(), faults()};
}

// make_examples finds them here (this library is linked whole: CMake OBJECT library).
[[maybe_unused]] const bool kListed = listExamples("bissc", bisscExamples);

}  // namespace busdecode
