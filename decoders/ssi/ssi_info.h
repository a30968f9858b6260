#pragma once
#include <memory>

#include "core/decoder.h"

namespace busdecode {

// The SSI decoder factory (registered by the built-in plugin; tests add it themselves).
std::shared_ptr<const DecoderFactory> makeSsiFactory();

}  // namespace busdecode
