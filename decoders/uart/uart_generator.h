#pragma once
// Test-signal source for UART lines (the Saleae SimulationDataGenerator idea): drives
// characters onto one line of a WaveBuilder with known truth, optionally with faults.
#include <cstdint>
#include <vector>

#include "core/waveform.h"
#include "uart_format.h"

namespace busdecode {

struct UartFaults {
    bool bad_parity = false;  // send the wrong parity bit
    bool bad_stop = false;    // send the (first) stop bit low
    double rate_error = 0;    // transmitter clock error, e.g. +0.02 = 2 % fast
};

class UartGenerator {
public:
    UartGenerator(WaveBuilder& wave, std::uint32_t line, UartFormat format)
        : wave_(wave), line_(line), fmt_(format) {}

    // Sends one character whose start bit begins at t_ns; returns the time (ns) at which
    // the stop bits end.
    double sendChar(double t_ns, std::uint32_t value, const UartFaults& faults = {});
    // Sends characters back to back with `gap_ns` of idle between them; returns the end.
    double sendChars(double t_ns, const std::vector<std::uint32_t>& values, double gap_ns = 0);
    // Holds the line low (space) for duration_ns, then idle.
    double sendBreak(double t_ns, double duration_ns);
    double bitNs(const UartFaults& faults = {}) const {
        return 1e9 / (fmt_.baud * (1 + faults.rate_error));
    }
    const UartFormat& format() const { return fmt_; }

private:
    void drive(double t_ns, bool logical) { wave_.setNs(line_, t_ns, logical != fmt_.invert); }

    WaveBuilder& wave_;
    std::uint32_t line_;
    UartFormat fmt_;
};

}  // namespace busdecode
