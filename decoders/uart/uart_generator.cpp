#include "uart_generator.h"

#include <algorithm>

namespace busdecode {

double UartGenerator::sendChar(double t_ns, std::uint32_t value, const UartFaults& faults) {
    const double bit = bitNs(faults);
    double t = t_ns;
    drive(t, false);  // start bit
    t += bit;
    for (int i = 0; i < fmt_.bits; ++i) {
        drive(t, fmt_.bitAt(value, i) != 0);
        t += bit;
    }
    if (fmt_.hasParityBit()) {
        drive(t, fmt_.parityBitFor(value) != faults.bad_parity);
        t += bit;
    }
    drive(t, !faults.bad_stop);
    if (faults.bad_stop) {
        // A low first stop bit, then the line returns to idle for the rest.
        t += bit * std::min(1.0, fmt_.stop_bits);
        drive(t, true);
        t += bit * (fmt_.stop_bits - std::min(1.0, fmt_.stop_bits));
        return t;
    }
    return t + bit * fmt_.stop_bits;
}

double UartGenerator::sendChars(double t_ns, const std::vector<std::uint32_t>& values,
                                double gap_ns) {
    double t = t_ns;
    for (auto v : values)
        t = sendChar(t, v) + gap_ns;
    return t - gap_ns;
}

double UartGenerator::sendBreak(double t_ns, double duration_ns) {
    drive(t_ns, false);
    drive(t_ns + duration_ns, true);
    return t_ns + duration_ns;
}

}  // namespace busdecode
