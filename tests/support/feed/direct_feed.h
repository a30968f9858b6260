#pragma once
// One decoder fed a capture directly, without a session (no read-ahead, no glitch
// filter, no other decoders), in one of the ways a decoder can take edges: through its
// general path (FastDecoder::edgeReference), one at a time through edge(), or in blocks
// through FastDecoder::edges(). A decoder with fast paths of its own must decode the same way
// whichever it is given; its tests and the fuzz harness compare the three.
#include <cstddef>
#include <string>
#include <vector>

#include "core/decoder.h"
#include "core/options.h"
#include "core/waveform.h"

namespace busdecode {

enum class Feed { Reference, OneByOne, Blocks };

// Decodes `w` with a fresh decoder from `factory`: line_of_role[r] is the line of `w`
// bound to role r, or -1. Only the bound lines' changes of level are fed, as a session
// would; `block` is the block size for Feed::Blocks. Returns each event as a JSON line
// (appendEventJson), then each line of advice as "advice: ...". Throws what the
// factory throws for options it refuses (InputError).
std::vector<std::string> decodeDirectly(const DecoderFactory& factory, const Options& options,
                                        const Waveform& w, const std::vector<int>& line_of_role,
                                        Feed feed, std::size_t block = 0);

}  // namespace busdecode
