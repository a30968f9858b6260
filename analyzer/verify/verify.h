#pragma once
// `decode verify CAPTURE... --rules FILE [--junit FILE] [--jobs N]`: checks every
// capture against rules; exit 0 all pass, 1 any fails, 2 bad input.
#include "app/decode_args.h"

namespace busdecode {

int runVerify(const DecodeArgs& args);

}  // namespace busdecode
