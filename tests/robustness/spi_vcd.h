#pragma once
// SPI captures (mode 3, 32-bit words, 1 ns timescale) for the CLI's exit-status tests:
// as long or as sparse as a test needs, decodable with `--proto spi` alone.
#include <cstdint>
#include <string>

#include "support/paths.h"

namespace busdecode::test {

// `words` words, one every `gap_ns` nanoseconds after the first at 1 us.
inline std::string spiVcd(int words, std::int64_t gap_ns) {
    std::string v =
        "$timescale 1 ns $end\n$scope module top $end\n"
        "$var wire 1 ! cs $end\n$var wire 1 \" sclk $end\n$var wire 1 # mosi $end\n"
        "$var wire 1 $ miso $end\n$upscope $end\n$enddefinitions $end\n"
        "#0 1! 1\" 0# 0$\n";
    std::uint32_t x = 12345;
    for (int w = 0; w < words; ++w) {
        std::int64_t t = 1000 + std::int64_t(w) * gap_ns;
        v += "#" + std::to_string(t) + " 0!\n";
        for (int b = 0; b < 32; ++b) {
            x = x * 1664525u + 1013904223u;
            t += 100;
            v += "#" + std::to_string(t) + " 0\" " + (x >> 31 ? "1#" : "0#") +
                 (x >> 30 & 1 ? " 1$" : " 0$") + "\n";
            v += "#" + std::to_string(t + 50) + " 1\"\n";
        }
        v += "#" + std::to_string(t + 200) + " 1!\n";
    }
    return v;
}

// Writes spiVcd(words, gap_ns) to tempDir()/name once and returns its path.
inline std::string spiCapture(const std::string& name, int words, std::int64_t gap_ns) {
    const std::string path = tempDir() + "/" + name;
    writeFile(path, spiVcd(words, gap_ns));
    return path;
}

// Rules for `decode verify` that decode SPI and ask for one transfer.
inline std::string spiRules() {
    const std::string path = tempDir() + "/spi_rules.toml";
    writeFile(path, "[decode]\nproto = [\"spi\"]\n[spi]\nmin_frames = 1\n");
    return path;
}

}  // namespace busdecode::test
