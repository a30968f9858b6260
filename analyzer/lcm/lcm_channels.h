#pragma once
// The contract's LCM channel names: one channel per event kind, DECODE_<PROTO>_<TYPE>,
// plus the annotation channel that carries every event and the run status channel.
#include <string>
#include <string_view>

namespace busdecode {

inline constexpr const char* kLcmEventsChannel = "DECODE_EVENTS";
inline constexpr const char* kLcmStatusChannel = "DECODE_STATUS";

// "bissc", "frame" -> "DECODE_BISSC_FRAME". Letters are upper-cased; characters LCM
// tools would choke on (anything but letters, digits and '_') become '_', so a plugin
// id such as "my-bus" still gets a usable channel ("DECODE_MY_BUS_...").
std::string lcmChannelFor(std::string_view proto, std::string_view type);

}  // namespace busdecode
