#pragma once
// The HTML report: the text report's content as one self-contained page (inline CSS and
// SVG, no scripts, nothing fetched) with pictures: position over time (decimated to a
// bounded number of points), histograms of the timing fields (line delay among them),
// and an annotated timing diagram of the first faulty event (see frame_layout.h).
#include <string>

#include "capture_stats.h"

namespace busdecode {

std::string renderHtmlReport(const CaptureStats& stats);

// Escapes &, <, >, " and ' for HTML text and attributes.
std::string htmlEscape(const std::string& s);

}  // namespace busdecode
