#pragma once
// Tiny VCD texts written by hand-rolled code, so CLI tests do not depend on the writers
// they might be testing.
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace busdecode::test {

class VcdText {
public:
    // names: line names (id chars assigned in order); initial levels
    VcdText(std::vector<std::string> names, std::vector<int> initial,
            const std::string& timescale = "1 ns");
    void set(int line, std::int64_t t, int level);
    std::string str(std::int64_t end) const;

    // Appends a UART byte (8N1, LSB first) on `line` starting at t; returns end time.
    std::int64_t uartByte(int line, std::int64_t t, int baud, std::uint8_t value);
    // SPI mode 3 (CPOL=1, CPHA=1), MSB first, CS low around `bits` clocks of period `period`.
    std::int64_t spiWord(int cs, int sclk, int mosi, int miso, std::int64_t t, std::int64_t period,
                         std::uint64_t out, std::uint64_t in, int bits);

private:
    std::vector<std::string> names_;
    std::vector<int> levels_;
    std::map<std::int64_t, std::vector<std::pair<int, int>>> changes_;
    std::string timescale_;
};

}  // namespace busdecode::test
