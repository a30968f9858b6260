#pragma once
// Example decoder: reports every pulse on one line with its width. Small on purpose:
// it shows the whole decoder interface (declaration as data, edges in, events out).
#include <core/registry.h>

namespace pulse {

std::shared_ptr<const busdecode::DecoderFactory> makePulseFactory();

}  // namespace pulse
