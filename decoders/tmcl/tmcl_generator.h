#pragma once
// Test traffic for the TMCL decoder: command/reply exchanges as UART characters, either
// on two lines (host -> module, module -> host) or on one half-duplex RS-485 line.
#include <cstdint>

#include "core/waveform.h"
#include "tmcl_datagram.h"
#include "uart_generator.h"

namespace busdecode {

class TmclTrafficGenerator {
public:
    // Two lines, or the same line twice for a half-duplex bus.
    TmclTrafficGenerator(WaveBuilder& wave, std::uint32_t host_line, std::uint32_t module_line,
                         double baud);

    // Sends a datagram from the host (or module) at t_ns; returns its end (ns).
    double sendFromHost(double t_ns, const tmcl::Datagram& d, double byte_gap_ns = 0);
    double sendFromModule(double t_ns, const tmcl::Datagram& d, double byte_gap_ns = 0);
    // A command, then after `turnaround_ns` the reply; returns the end of the reply.
    double exchange(double t_ns, const tmcl::Datagram& command, const tmcl::Datagram& reply,
                    double turnaround_ns);
    double charNs() const { return 10 * host_.bitNs(); }

private:
    UartGenerator host_, module_;
};

}  // namespace busdecode
