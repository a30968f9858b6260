#pragma once
// The plain-text report: capture facts, per-bus counts, timing statistics with small
// text histograms, position range and largest jump, the first faults.
#include <string>

#include "capture_stats.h"

namespace busdecode {

std::string renderTextReport(const CaptureStats& stats);

}  // namespace busdecode
