#include "baud_estimator.h"

#include <algorithm>
#include <cmath>

namespace busdecode {

void BaudEstimator::addEdge(Tick t, int line, bool level) {
    if (line < 0 || line >= int(last_.size())) return;
    if (last_[line] != kNoTick && t > last_[line]) {
        widths_.push_back(t - last_[line]);
        idle_level_.push_back(level != idle_high_);  // the pulse it ends had the other level
    }
    last_[line] = t;
}

std::optional<double> BaudEstimator::measuredBaud(const Timebase& tb) const {
    if (widths_.empty()) return std::nullopt;
    std::vector<Tick> sorted = widths_;
    std::sort(sorted.begin(), sorted.end());
    // The bit time is the shortest pulse that most pulses are whole multiples of; a
    // glitch is shorter still but explains nothing else, so it is passed over.
    // Sums over the start bit's level (sum_*[0]) and the idle level ([1]).
    auto fit = [&](double bit, double(&sum_width)[2], double(&sum_bits)[2]) {
        std::size_t consistent = 0;
        sum_width[0] = sum_width[1] = sum_bits[0] = sum_bits[1] = 0;
        for (std::size_t i = 0; i < widths_.size(); ++i) {
            const double w = double(widths_[i]);
            const double n = std::round(w / bit);
            if (n < 1 || n > 12) continue;
            // Within a quarter bit of a whole number of bits (not a quarter per bit: a
            // candidate a fraction of the real bit would fit every long pulse).
            if (std::fabs(w - n * bit) > 0.25 * bit) continue;
            sum_width[idle_level_[i]] += w;
            sum_bits[idle_level_[i]] += n;
            ++consistent;
        }
        return consistent;
    };
    double bit_ticks = double(sorted.front());
    Tick tried = -1;
    int candidates = 0;
    for (Tick w : sorted) {
        if (w == tried) continue;
        tried = w;
        if (++candidates > 32) break;
        double sum_width[2], sum_bits[2];
        if (2 * fit(double(w), sum_width, sum_bits) >= widths_.size()) {
            // Averaged over every pulse of 1..12 bits: sampling quantises each edge by up
            // to a tick, and long pulses measure the bit time more precisely. At the start
            // bit's level, if any: only bits make those (an idle gap shorter than a quarter
            // bit after the stop bit would pass for part of it).
            const int level = sum_bits[0] > 0 ? 0 : 1;
            bit_ticks = sum_width[level] / sum_bits[level];
            break;
        }
    }
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
