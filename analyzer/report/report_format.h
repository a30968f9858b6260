#pragma once
// Small text helpers shared by the text and HTML reports.
#include <cstdint>
#include <string>
#include <vector>

#include "quantile_sketch.h"

namespace busdecode {

// "12.500 MHz", "250.000 kHz", "12 Hz".
std::string formatFrequency(double hz);
// A statistic of a timing field in the unit its name implies (`_ns`, `_us`, `_hz`), or a
// plain number (`_cycles`, `repeats`).
std::string formatFieldValue(const std::string& key, double v);
// Bytes as "1.2 MB".
std::string formatBytes(std::uint64_t bytes);
// Rows of a small text histogram of the sketch: "  120 ns .. 130 ns  |######    |  500".
std::vector<std::string> textHistogram(const std::string& key, const QuantileSketch& s, int bins,
                                       int width);
// The time of a tick in the capture, as the reports print it.
std::string formatTime(double ns);

}  // namespace busdecode
