#pragma once
// The session's parallel path: a VCD file's pieces decoded ahead on the reader's threads
// (piece_speculation.h) and spliced in on the decoding thread. Used where the reader cuts
// the file in pieces (capture/piece_work.h) and the one decoder is a FastDecoder that is
// also a SpliceableDecoder; everywhere else the session decodes in order alone.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "block_decoding.h"
#include "capture/capture_reader.h"
#include "capture/piece_work.h"
#include "event_pool.h"
#include "piece_speculation.h"

namespace busdecode {

class ParallelVcdPipeline {
public:
    // What the session's one decoder was made and started with.
    struct DecoderSetup {
        const DecoderFactory& factory;
        const Options& options;
        const DecoderContext& ctx;
        const FastPathHints& hints;
        const std::string& instance;
    };
    // Null where it does not apply (a reader without pieces, a decoder that cannot be
    // spliced). `decoder`: the session's, replaced by each spliced piece's; `sink`: where
    // spliced-in events go; `spare`: the session's recycled events, from now on shared
    // with the pieces' threads. Call before the first next().
    static std::unique_ptr<ParallelVcdPipeline> start(CaptureReader& reader,
                                                      const DecoderSetup& setup,
                                                      const std::vector<int>& role_of_line,
                                                      std::unique_ptr<Decoder>& decoder,
                                                      EventSink& sink, RecycledEvents& spare);

    // The block [first, last) just read, `taken` edges handed out before it: decoded in
    // order or through a splice point. False: the decoder that decodes on from here
    // decoded it already (and was advanced past it); the caller does not advance it.
    bool decode(const Edge* first, const Edge* last, std::uint64_t taken);
    const SpeculationSplicer::Stats& stats() const { return splicer_.stats(); }
    // How far the decoder has decoded, which may be past the blocks handed to decode().
    Tick decodedUntil() const { return splicer_.decodedUntil(); }

    ParallelVcdPipeline(PieceReader& pieces, std::shared_ptr<EventPool> pool,
                        std::shared_ptr<EventPool> other_pool, std::unique_ptr<Decoder>& decoder,
                        EventSink& sink, const int* role_of_line);

private:
    PieceReader& pieces_;
    // The pools the session's recycled events go back to: the decoding thread's pieces'
    // and the other reader thread's (EventHome 1). They outlive `spare` (the session
    // keeps this object declared before it).
    std::shared_ptr<EventPool> pool_, other_pool_;
    SpeculationSplicer splicer_;
};

}  // namespace busdecode
