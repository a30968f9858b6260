#pragma once
// Pipelining for two cores: a CaptureReader that runs another reader's next() on its
// own thread, a few blocks ahead, while the caller decodes the previous block. Reading
// and tokenising a text capture costs about as much as decoding it, so the two overlap.
//
// Behaviour is that of the wrapped reader, block for block: the same edges in the same
// blocks, its InputError rethrown by next() at the point where the wrapped reader threw
// it (after every block before it has been handed out), and a followed capture handed
// on as soon as the wrapped reader returns a block. memoryReader and unit tests keep the
// single-threaded path by not wrapping.
#include <memory>

#include "capture_reader.h"

namespace busdecode {

// `ahead`: blocks read ahead at most (memory: ahead * kEdgeBlockSize edges).
std::unique_ptr<CaptureReader> prefetchReader(std::unique_ptr<CaptureReader> inner, int ahead = 32);

}  // namespace busdecode
