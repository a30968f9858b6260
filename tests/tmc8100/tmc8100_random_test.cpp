// Robustness: random levels on every line (seeded) through the SPI and TMC8100 layers in
// every mode. Nothing may throw; events come out in start order with start <= end; every
// datagram the SPI layer completes becomes exactly one TMC8100 command.
#include <gtest/gtest.h>

#include <random>

#include "core/session.h"
#include "event_expect.h"

using namespace busdecode;
using namespace busdecode::test;

TEST(Tmc8100Random, NoiseOnEveryLine) {
    registerDecoders();
    std::mt19937 rng(8100);
    for (int round = 0; round < 8; ++round) {
        SCOPED_TRACE(round);
        WaveBuilder wb(Timebase{1, 1'000'000'000}, {"cs", "sclk", "mosi", "miso", "gpio6"},
                       {1, 1, 0, 0, 0});
        Tick t = 10;
        for (int i = 0; i < 20000; ++i) {
            t += 1 + Tick(rng() % 50);
            // cs toggles rarely so that whole datagrams happen; the rest toggle often.
            std::uint32_t line = rng() % 100 < 2 ? 0 : 1 + rng() % 4;
            wb.set(line, t, !wb.level(line));
        }
        Waveform w = wb.build(t + 100);
        std::map<std::string, std::string> opts = {{"cpol", std::to_string(round & 1)},
                                                   {"cpha", std::to_string((round >> 1) & 1)},
                                                   {"mode", round < 4 ? "auto" : "app"}};
        std::map<std::string, std::string> spi_opts = {{"cpol", opts["cpol"]},
                                                       {"cpha", opts["cpha"]}};
        if (round == 7) opts["bits"] = spi_opts["bits"] = "8";  // bytes joined into datagrams
        std::vector<Event> events;
        ASSERT_NO_THROW(events = decodeWaveform(w, {DecoderRequest{"tmc8100", {}, opts},
                                                    DecoderRequest{"spi", {}, spi_opts}}));
        ASSERT_FALSE(events.empty());
        for (std::size_t i = 0; i < events.size(); ++i) {
            EXPECT_LE(events[i].start, events[i].end) << events[i].summary;
            if (i > 0) {
                EXPECT_LE(events[i - 1].start, events[i].start);
            }
        }
        if (round != 7) {
            EXPECT_EQ(only(events, "tmc8100", "command").size(), only(events, "spi").size());
        }
    }
}
