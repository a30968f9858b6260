#include "baud_estimator.h"

#include <algorithm>
#include <cmath>

namespace busdecode {

void BaudEstimator::addEdge(Tick t, int line) {
    if (line < 0 || line >= int(last_.size())) return;
    if (last_[line] != kNoTick && t > last_[line]) widths_.push_back(t - last_[line]);
    last_[line] = t;
}

std::optional<double> BaudEstimator::measuredBaud(const Timebase& tb) const {
    if (widths_.empty()) return std::nullopt;
    const double shortest = double(*std::min_element(widths_.begin(), widths_.end()));
    // Average over pulses of 1..12 bits: sampling quantises each edge by up to a tick,
    // and long pulses measure the bit time far more precisely than the shortest one.
    double sum_width = 0, sum_bits = 0;
    for (Tick w : widths_) {
        const double n = std::round(double(w) / shortest);
        if (n < 1 || n > 12) continue;
        if (std::fabs(double(w) / n - shortest) > 0.25 * shortest) continue;
        sum_width += double(w);
        sum_bits += n;
    }
    const double bit_ticks = sum_bits > 0 ? sum_width / sum_bits : shortest;
    return 1.0 / (bit_ticks * tb.secondsPerTick());
}

double BaudEstimator::snapToStandard(double baud) {
    static const double kRates[] = {110,     300,     600,     1200,    2400,   4800,   9600,
                                    14400,   19200,   28800,   31250,   38400,  57600,  76800,
                                    115200,  128000,  230400,  250000,  460800, 500000, 921600,
                                    1000000, 1500000, 2000000, 3000000, 4000000};
    double best = baud, best_err = 0.04;
    for (double r : kRates) {
        const double err = std::fabs(baud - r) / r;
        if (err < best_err) {
            best = r;
            best_err = err;
        }
    }
    return best;
}

}  // namespace busdecode
