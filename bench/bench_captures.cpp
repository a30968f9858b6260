#include "bench_captures.h"

#include <random>
#include <stdexcept>

#include "core/registry.h"

#ifdef BENCH_HAVE_SPI
#include "spi_generator.h"
#include "spi_info.h"
#endif
#ifdef BENCH_HAVE_UART
#include "uart_decoder.h"
#include "uart_generator.h"
#endif
#ifdef BENCH_HAVE_BISSC
#include "bissc_decoder.h"
#include "bissc_generator.h"
#endif
#ifdef BENCH_HAVE_SSI
#include "ssi_generator.h"
#include "ssi_info.h"
#endif
#ifdef BENCH_HAVE_TMCL
#include "tmcl_decoder.h"
#include "tmcl_generator.h"
#endif
#ifdef BENCH_HAVE_TMC8100
#include "tmc8100_decoder.h"
#include "tmc8100_generator.h"
#endif

namespace busdecode::bench {

namespace {

const Timebase kTb = Timebase::fromSampleRate(kSampleRateHz);

#ifdef BENCH_HAVE_SPI
// SPI at 10 MHz, back to back: eight 32-bit words per chip select, 100 ns between
// transfers; the data lines return low at the end so chunks join seamlessly. Random
// words, or with `periodic` the same two words every time (0xAAAAAAAA on MOSI, 0x55555555
// on MISO): the same timing, a data line changing at every bit, and an edge sequence
// that repeats exactly, so that every branch of the reader and the decoder can be
// predicted (bench/README.md: what unpredictable data costs).
BenchBus spiBus(int transfers, std::mt19937& rng, bool periodic) {
    SpiMode mode;  // CPOL=1, CPHA=1, MSB first: the contract defaults
    SpiTiming timing;
    timing.period_ns = 100;
    timing.cs_setup_ns = 50;
    timing.cs_hold_ns = 50;
    timing.data_delay_ns = 20;
    WaveBuilder wb(kTb, {"cs", "sclk", "mosi", "miso"}, SpiGenerator::idleLevels(mode));
    SpiGenerator gen(wb, SpiLines{0, 1, 2, 3}, mode, timing);
    std::uniform_int_distribution<std::uint32_t> word;
    double t = 100;
    for (int i = 0; i < transfers; ++i) {
        std::vector<SpiGenerator::Word> words(8);
        for (auto& w : words)
            w = periodic ? SpiGenerator::Word{0xAAAAAAAAu, 0x55555555u}
                         : SpiGenerator::Word{word(rng), word(rng)};
        t = gen.transfer(t, words, 32);
        wb.setNs(2, t, false);
        wb.setNs(3, t, false);
        t += 100;
    }
    BenchBus b;
    b.id = periodic ? "spi-periodic" : "spi";
    b.chunk = wb.build(wb.ticksFromNs(t));
    b.requests = {{"spi", {}, {}}};
    b.decode_args = "--proto spi";
    b.sigrok_args =
        "-P spi:cs=cs:clk=sclk:mosi=mosi:miso=miso:cpol=1:cpha=1:wordsize=32 -A spi=mosi-data";
    return b;
}
#endif

#ifdef BENCH_HAVE_UART
// UART at 1 Mbaud 8N1 on tx and rx, characters back to back.
BenchBus uartBus(int chars, std::mt19937& rng) {
    UartFormat f;
    f.baud = 1'000'000;
    WaveBuilder wb(kTb, {"tx", "rx"}, {1, 1});
    UartGenerator tx(wb, 0, f), rx(wb, 1, f);
    std::uniform_int_distribution<std::uint32_t> byte(0, 255);
    std::vector<std::uint32_t> a(static_cast<std::size_t>(chars)),
        b(static_cast<std::size_t>(chars));
    for (auto& v : a)
        v = byte(rng);
    for (auto& v : b)
        v = byte(rng);
    double end = std::max(tx.sendChars(1000, a), rx.sendChars(1500, b));
    BenchBus bus;
    bus.id = "uart";
    bus.chunk = wb.build(wb.ticksFromNs(end + 2000));
    bus.requests = {{"uart", {}, {{"baud", "1000000"}}}};
    bus.decode_args = "--proto uart --opt baud=1000000";
    bus.sigrok_args = "-P uart:tx=tx:rx=rx:baudrate=1000000 -A uart=tx-data";
    return bus;
}
#endif

#ifdef BENCH_HAVE_BISSC
// BiSS-C at 10 MHz, 26 position bits, frames back to back (2 us timeout, 1 us idle).
// Random positions, or with `periodic` 0x2AAAAAA in every frame (see spiBus).
BenchBus bisscBus(int frames, std::mt19937& rng, bool periodic) {
    BisscGenConfig cfg;
    cfg.timebase = kTb;
    cfg.clock_hz = 10e6;
    cfg.bits = 26;
    cfg.line_delay_ns = 40;
    cfg.timeout_ns = 2000;
    cfg.idle_ns = 1000;
    cfg.lead_ns = 1000;
    cfg.names = {"ma", "sl"};
    BisscGenerator gen(cfg);
    std::uniform_int_distribution<std::uint64_t> pos(0, (1u << 26) - 1);
    for (int i = 0; i < frames; ++i) {
        BisscFrameSpec f;
        f.data = periodic ? 0x2AAAAAAu : pos(rng);
        gen.addFrame(f);
    }
    gen.pause(1000);
    BenchBus b;
    b.id = periodic ? "bissc-periodic" : "bissc";
    b.chunk = gen.build();
    b.requests = {{"bissc", {}, {}}};
    b.decode_args = "--proto bissc";
    // sigrok has no BiSS-C decoder: its SPI decoder on the same lines (MA as the clock,
    // SL as MISO, no chip select) does the comparable per-sample work.
    b.sigrok_args = "-P spi:clk=ma:miso=sl:cpol=1:cpha=1:wordsize=8 -A spi=miso-data";
    return b;
}
#endif

#ifdef BENCH_HAVE_SSI
// SSI at 1 MHz, 25-bit words, 20 us monoflop, 25 us between readings.
BenchBus ssiBus(int frames, std::mt19937& rng) {
    SsiGenConfig cfg;
    cfg.sample_rate_hz = kSampleRateHz;
    cfg.clock_hz = 1e6;
    cfg.tail_ns = 30000;
    std::vector<SsiGenFrame> fs(static_cast<std::size_t>(frames));
    std::uniform_int_distribution<std::uint64_t> word(0, (1u << 25) - 1);
    for (auto& f : fs) {
        f.word = word(rng);
        f.pause_ns = 25000;
    }
    BenchBus b;
    b.id = "ssi";
    b.chunk = generateSsi(cfg, fs).wave;
    b.requests = {{"ssi", {}, {}}};
    b.decode_args = "--proto ssi";
    b.sigrok_args = "-P ssi32:clk=clk:data=data -A ssi32";
    return b;
}
#endif

#ifdef BENCH_HAVE_TMCL
// TMCL at 115200 baud on two lines: SAP commands and their replies.
BenchBus tmclBus(int exchanges, std::mt19937& rng) {
    WaveBuilder wb(kTb, {"host", "module"}, {1, 1});
    TmclTrafficGenerator gen(wb, 0, 1, 115200);
    std::uniform_int_distribution<std::int32_t> value(-100000, 100000);
    double t = 1000;
    for (int i = 0; i < exchanges; ++i) {
        const std::int32_t v = value(rng);
        t = gen.exchange(t, tmcl::makeCommand(1, 5, 4, 0, v), tmcl::makeReply(2, 1, 100, 5, v),
                         20000) +
            20000;
    }
    BenchBus b;
    b.id = "tmcl";
    b.chunk = wb.build(wb.ticksFromNs(t));
    b.requests = {{"tmcl", {}, {{"baud", "115200"}}}};
    b.decode_args = "--proto tmcl --opt baud=115200";
    b.sigrok_args = "-P uart:tx=host:rx=module:baudrate=115200 -A uart=tx-data";
    return b;
}
#endif

#ifdef BENCH_HAVE_TMC8100
// TMC8100 encoder reads: command, SSI frame, GPIO6, three replies, over and over.
BenchBus tmc8100Bus(int reads, std::mt19937& rng) {
    Tmc8100Scenario sc;
    std::uniform_int_distribution<int> st(0, 65535);
    for (int i = 0; i < reads; ++i) {
        Tmc8100Scenario::EncoderRead r;
        r.ssi_word = Tmc8100Scenario::ssiWord(0, std::uint8_t(i & 63), std::uint16_t(st(rng)));
        sc.readEncoder(r);
        sc.pause(5000);
    }
    BenchBus b;
    b.id = "tmc8100";
    b.chunk = sc.build();
    b.requests = {{"tmc8100", {}, {}}};
    b.decode_args = "--proto tmc8100";
    b.sigrok_args =
        "-P spi:cs=spi_csn:clk=spi_sclk:mosi=spi_sdi:miso=spi_sdo:cpol=1:cpha=1:wordsize=32 -A "
        "spi=mosi-data";
    return b;
}
#endif

}  // namespace

std::vector<std::string> availableBuses() {
    std::vector<std::string> out;
#ifdef BENCH_HAVE_SPI
    out.push_back("spi");
    out.push_back("spi-periodic");
#endif
#ifdef BENCH_HAVE_UART
    out.push_back("uart");
#endif
#ifdef BENCH_HAVE_BISSC
    out.push_back("bissc");
    out.push_back("bissc-periodic");
#endif
#ifdef BENCH_HAVE_SSI
    out.push_back("ssi");
#endif
#ifdef BENCH_HAVE_TMCL
    out.push_back("tmcl");
#endif
#ifdef BENCH_HAVE_TMC8100
    out.push_back("tmc8100");
#endif
    return out;
}

BenchBus makeBus(const std::string& id, int units, std::uint32_t seed) {
    std::mt19937 rng(seed);
#ifdef BENCH_HAVE_SPI
    if (id == "spi" || id == "spi-periodic") return spiBus(units, rng, id != "spi");
#endif
#ifdef BENCH_HAVE_UART
    if (id == "uart") return uartBus(units, rng);
#endif
#ifdef BENCH_HAVE_BISSC
    if (id == "bissc" || id == "bissc-periodic") return bisscBus(units, rng, id != "bissc");
#endif
#ifdef BENCH_HAVE_SSI
    if (id == "ssi") return ssiBus(units, rng);
#endif
#ifdef BENCH_HAVE_TMCL
    if (id == "tmcl") return tmclBus(units, rng);
#endif
#ifdef BENCH_HAVE_TMC8100
    if (id == "tmc8100") return tmc8100Bus(units, rng);
#endif
    (void)units;
    (void)rng;
    throw std::invalid_argument("no benchmark bus '" + id + "' in this build");
}

void registerDecoders() {
#ifdef BENCH_HAVE_SPI
    Registry::instance().add(makeSpiFactory());
#endif
#ifdef BENCH_HAVE_UART
    Registry::instance().add(makeUartFactory());
#endif
#ifdef BENCH_HAVE_BISSC
    Registry::instance().add(makeBisscFactory());
#endif
#ifdef BENCH_HAVE_SSI
    Registry::instance().add(makeSsiFactory());
#endif
#ifdef BENCH_HAVE_TMCL
    Registry::instance().add(makeTmclFactory());
#endif
#ifdef BENCH_HAVE_TMC8100
    Registry::instance().add(makeTmc8100Factory());
#endif
}

}  // namespace busdecode::bench
