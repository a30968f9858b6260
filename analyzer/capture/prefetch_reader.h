#pragma once
// Pipelining for two cores: a CaptureReader that runs another reader's next() on its
// own thread, a few blocks ahead, while the caller decodes the previous block. Reading
// and tokenising a text capture costs about as much as decoding it, so the two overlap.
//
// Behaviour is that of the wrapped reader, block for block: the same edges in the same
// blocks, its InputError rethrown by next() at the point where the wrapped reader threw
// it (after every block before it has been handed out), and a followed capture handed
// on as soon as the wrapped reader returns a block (`batch` below). memoryReader and unit tests
// keep the single-threaded path by not wrapping.
#include <memory>

#include "capture_reader.h"

namespace busdecode {

// `ahead`: blocks read ahead at most (memory: ahead * kEdgeBlockSize edges). A full queue
// refills from half empty: the reader is woken once per ahead/2 blocks, not per block.
// `batch`: a decoder that finds the queue empty waits for this many blocks, or for a
// block short of full, or the end: fewer wake-ups of the reader's thread when it is the
// slower one. Only for a reader that never waits for input (a regular file, not
// followed): a live input keeps 1, so that each block is handed on as soon as it is read.
// decode's choices (decode_args.cpp; bench/read_capture --prefetch times the same).
inline constexpr int kReadAheadBlocks = 32;
inline constexpr int kWholeFileBatch = 4;
std::unique_ptr<CaptureReader> prefetchReader(std::unique_ptr<CaptureReader> inner,
                                              int ahead = kReadAheadBlocks, int batch = 1);

}  // namespace busdecode
