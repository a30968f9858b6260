// Writes the BiSS-C example captures (captures/bissc_*) from the generator, so they can
// be remade exactly: `make_bissc_examples <repo>/captures`.
//   bissc_1mhz_26bit.vcd      26-bit frames at 1 MHz, 300 ns line delay, processing time,
//                             a register read (0x7E -> 0x12) and a write over CDM/CDS
//   bissc_10mhz_long_cable.csv  32-bit frames at 10 MHz with a 1.2 us line delay (12 bit
//                             times), sigrok dense CSV at 100 MHz
//   bissc_errors.vcd          bad CRC, nE/nW active, a truncated frame, Hold-CDM
#include <cstdio>
#include <random>
#include <string>

#include "bissc_generator.h"
#include "capture/capture_writer.h"

using namespace busdecode;

namespace {

void readAndWrite(const std::string& dir) {
    BisscGenConfig cfg;
    cfg.clock_hz = 1e6;
    cfg.bits = 26;
    cfg.line_delay_ns = 300;
    cfg.timeout_ns = 20000;
    cfg.idle_ns = 5000;
    BisscGenerator gen(cfg);
    ControlItemSpec rd;
    rd.kind = ControlItemSpec::Kind::Read;
    rd.address = 0x7E;
    rd.data = {0x12};
    ControlItemSpec wr;
    wr.kind = ControlItemSpec::Kind::Write;
    wr.address = 0x48;
    wr.data = {0xA5};
    wr.busy = {0};
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
    writeVcd(gen.build(), dir + "/bissc_1mhz_26bit.vcd");
}

void longCable(const std::string& dir) {
    BisscGenConfig cfg;
    cfg.timebase = Timebase::fromSampleRate(100'000'000);
    cfg.clock_hz = 10e6;
    cfg.bits = 32;
    cfg.line_delay_ns = 1200;
    cfg.timeout_ns = 15000;
    cfg.idle_ns = 3000;
    BisscGenerator gen(cfg);
    std::mt19937_64 rng(32);
    for (int i = 0; i < 6; ++i) {
        BisscFrameSpec f;
        f.data = rng() & 0xFFFFFFFFull;
        f.proc_cycles = 5;
        f.extra_clocks = 4;
        gen.addFrame(f);
    }
    writeCsv(gen.build(), dir + "/bissc_10mhz_long_cable.csv", CsvDialect::SigrokDense);
}

void errors(const std::string& dir) {
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
    writeVcd(gen.build(), dir + "/bissc_errors.vcd");
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: make_bissc_examples CAPTURE_DIR\n");
        return 2;
    }
    const std::string dir = argv[1];
    readAndWrite(dir);
    longCable(dir);
    errors(dir);
    return 0;
}
