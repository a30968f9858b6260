#pragma once
// --lcm [URL]: publishes every event as a typed LCM message while decoding
// (DECODE_<PROTO>_<TYPE>) plus the generic annotation on DECODE_EVENTS.
#include <memory>
#include <string>

#include "core/session.h"

namespace busdecode {

// url "" = LCM's default. Throws InputError when the URL is bad or the network is
// unavailable. The sink prints a count of dropped messages at the end, if any.
// `name_capture`: the annotations' json names its capture (several in one call).
std::unique_ptr<OutputSink> makeLcmSink(const std::string& url, bool name_capture = false);
// Ends the run on a sink from makeLcmSink (LcmSink::close): InputError when a log file it
// wrote does not hold what it published.
void closeLcmSink(OutputSink& sink);

}  // namespace busdecode
