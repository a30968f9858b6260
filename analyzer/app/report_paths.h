#pragma once
// Where --report writes when several captures are decoded in one call: one report per
// capture, named after it, and never two captures on one file.
#include <string>
#include <vector>

namespace busdecode {

// One path per capture. A single capture: `report` itself. Several: the capture's file
// name inserted before the report's extension ("r.txt", "d/x.vcd" -> "r-x.vcd.txt"), and
// a name already given to an earlier capture (same file name in another directory, the
// same capture twice) gets "-2", "-3"... after it ("r-x.vcd-2.txt"). A device or FIFO
// (`--report /dev/null`) takes every capture's report in turn: no file is made beside it.
std::vector<std::string> reportPaths(const std::string& report,
                                     const std::vector<std::string>& captures);

}  // namespace busdecode
