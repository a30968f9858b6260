#pragma once
// Turns one decoded event into its LCM messages: the typed message of its kind (or the
// generic event_fields_t) on DECODE_<PROTO>_<TYPE>, and the annotation on DECODE_EVENTS.
// Fields are taken by name (Event::get); a null or missing contract field is listed in
// the message's null_fields and left 0 / false / "" / NaN.
#include <cstdint>
#include <string>
#include <string_view>

#include "core/event.h"
#include "core/time.h"

namespace lcm {
class LCM;
}

namespace busdecode {

// True when the contract has a typed message for proto/type (ssi/frame, bissc/frame,
// ...); other events are published as the generic event_fields_t.
bool hasTypedLcmMessage(std::string_view proto, std::string_view type);

struct LcmPublishResult {
    std::string channel;  // the typed (or generic) channel
    int failures = 0;     // publish calls LCM refused (0, 1 or 2)
};

// Publishes both messages of `e`, stamped with `seq` and the wall-clock time now.
// `capture_fields`: captureJsonFields() of the event's capture, for the annotation's json.
LcmPublishResult publishEventToLcm(lcm::LCM& lc, const Event& e, const Timebase& tb,
                                   std::int64_t seq, std::string_view capture_fields = {});

// Wall-clock microseconds since the Unix epoch (LCM's utime).
std::int64_t lcmUtimeNow();

}  // namespace busdecode
