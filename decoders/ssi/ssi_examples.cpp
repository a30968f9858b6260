#include "ssi_examples.h"

#include <utility>

#include "capture/capture_reader.h"
#include "core/gray.h"
#include "core/session.h"
#include "sinks/event_format.h"

namespace busdecode {

namespace {

SsiExample tmc8100() {
    // The TMC8100 application note's frame: 25 bits, 26 clocks at 1 MHz, bits 23/22
    // diagnostic, 16-bit Gray single-turn; one re-read while data is still low.
    SsiGenConfig cfg;
    cfg.data_bits = 25;
    cfg.clock_hz = 1e6;
    cfg.tm_ns = 20000;
    cfg.seed = 8100;
    std::vector<SsiGenFrame> frames = {
        {binaryToGray(0x1234), 0, 1, 20000, {}},
        {binaryToGray(0x1240), 0, 1, 60000, {}},
        {binaryToGray(0x1240), 0, 1, 8000, {}},  // re-read within tm
        {(1u << 22) | binaryToGray(0x7FFF), 0, 1, 60000, {}},
        {(1u << 23) | binaryToGray(0x8000), 0, 1, 60000, {}},
    };
    auto gen = generateSsi(cfg, frames);
    return {{"ssi_tmc8100_gray25.vcd",
             ExampleFormat::Vcd,
             "TMC8100 note layout: 25-bit word, 16-bit Gray position, status bits 23/22, a re-read",
             {{"ssi",
               {},
               {{"bits", "25"},
                {"st_bits", "16"},
                {"gray", "1"},
                {"status_bits", "out_of_range@23,low_quality@22"}}}},
             std::move(gen.wave)},
            std::move(gen.frames)};
}

SsiExample posital() {
    // The POSITAL note's word 0x010014ED: the master counts the idle 1 at the first falling
    // edge as bit 24, then 12-bit multi-turn and 12-bit single-turn (MT 1, 110.83 deg).
    SsiGenConfig cfg;
    cfg.data_bits = 24;
    cfg.lead = true;
    cfg.clock_hz = 250e3;
    cfg.tm_ns = 25000;
    cfg.sample_rate_hz = 10'000'000;
    cfg.seed = 14;
    std::vector<SsiGenFrame> frames = {
        {0x0014ED, 0, 1, 30000, {}},
        {0x0014F0, 0, 1, 80000, {}},
        {0x002001, 0, 1, 80000, {}},
    };
    auto gen = generateSsi(cfg, frames);
    return {
        {"ssi_posital_lead.csv",
         ExampleFormat::SigrokCsv,
         "POSITAL note example 0x010014ED at 250 kHz (sigrok CSV, 10 MHz samples)",
         {{"ssi",
           {},
           {{"bits", "25"}, {"lead", "1"}, {"mt_bits", "12"}, {"st_bits", "12"}, {"tm_us", "25"}}}},
         std::move(gen.wave)},
        std::move(gen.frames)};
}

SsiExample ringShift() {
    // Multiple transmission at 500 kHz over a long cable (400 ns delay) with clock jitter:
    // triple reads, one of them with a corrupted repeat, and a truncated last burst.
    SsiGenConfig cfg;
    cfg.data_bits = 25;
    cfg.clock_hz = 500e3;
    cfg.delay_ns = 400;
    cfg.jitter_ns = 40;
    cfg.tm_ns = 16000;
    cfg.seed = 25;
    std::vector<SsiGenFrame> frames = {
        {binaryToGray(0x0ABC1234), 0, 3, 20000, {}},
        {binaryToGray(0x0ABC1240), 0, 3, 80000, {{2, 20}}},
        {binaryToGray(0x0ABC1250), 0, 2, 80000, {}},
        {binaryToGray(0x0ABC1260), 12, 1, 80000, {}},
    };
    auto gen = generateSsi(cfg, frames);
    return {
        {"ssi_ringshift_delay.vcd",
         ExampleFormat::Vcd,
         "25-bit Gray MT/ST, ring shift x3 with one corrupted repeat, 400 ns delay, jitter, "
         "a truncated burst",
         {{"ssi",
           {},
           {{"bits", "25"}, {"st_bits", "13"}, {"mt_bits", "12"}, {"gray", "1"}, {"tm_us", "16"}}}},
         std::move(gen.wave)},
        std::move(gen.frames)};
}

SsiExample saleae() {
    // A 13-bit single-turn encoder at 2 MHz exported the Saleae Logic 2 way.
    SsiGenConfig cfg;
    cfg.data_bits = 13;
    cfg.clock_hz = 2e6;
    cfg.tm_ns = 20000;
    cfg.clk_name = "CLK";
    cfg.data_name = "DATA";
    cfg.seed = 13;
    std::vector<SsiGenFrame> frames = {
        {binaryToGray(0x1234), 0, 1, 10000, {}},
        {binaryToGray(0x1FFF), 0, 1, 40000, {}},
        {binaryToGray(0x0000), 0, 2, 40000, {}},
    };
    auto gen = generateSsi(cfg, frames);
    return {{"ssi_singleturn_2mhz.csv",
             ExampleFormat::SaleaeCsv,
             "13-bit Gray single-turn at 2 MHz (Saleae Logic 2 CSV)",
             {{"ssi", {}, {{"bits", "13"}, {"st_bits", "13"}, {"gray", "1"}}}},
             std::move(gen.wave)},
            std::move(gen.frames)};
}

}  // namespace

std::vector<SsiExample> ssiExamples() {
    return {tmc8100(), posital(), ringShift(), saleae()};
}

// make_examples finds them here (this library is linked whole: CMake OBJECT library).
[[maybe_unused]] const bool kListed = listExamples("ssi", ssiExamples);

}  // namespace busdecode
