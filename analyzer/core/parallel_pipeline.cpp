#include "parallel_pipeline.h"

#include "splicing.h"

namespace busdecode {

std::unique_ptr<ParallelVcdPipeline> ParallelVcdPipeline::start(
    CaptureReader& reader, const DecoderSetup& setup, const std::vector<int>& role_of_line,
    std::unique_ptr<Decoder>& decoder, EventSink& sink, RecycledEvents& spare) {
    auto* pieces = dynamic_cast<PieceReader*>(&reader);
    if (!pieces || !reader.changesOnly() || !fastPathOf(*decoder) || !splicingOf(*decoder))
        return nullptr;
    DecoderContext ctx = setup.ctx;
    ctx.sink = nullptr;
    auto pool = std::make_shared<EventPool>();
    auto other_pool = std::make_shared<EventPool>();
    if (!pieces->setPieceWork(std::make_shared<PieceSpeculator>(setup.factory, setup.options, ctx,
                                                                setup.hints, role_of_line, pool,
                                                                other_pool, setup.instance)))
        return nullptr;
    spare.setShared(pool.get());
    spare.sendHome(other_pool.get());
    return std::make_unique<ParallelVcdPipeline>(*pieces, std::move(pool), std::move(other_pool),
                                                 decoder, sink, role_of_line.data());
}

ParallelVcdPipeline::ParallelVcdPipeline(PieceReader& pieces, std::shared_ptr<EventPool> pool,
                                         std::shared_ptr<EventPool> other_pool,
                                         std::unique_ptr<Decoder>& decoder, EventSink& sink,
                                         const int* role_of_line)
    : pieces_(pieces),
      pool_(std::move(pool)),
      other_pool_(std::move(other_pool)),
      splicer_(decoder, sink, role_of_line) {}

bool ParallelVcdPipeline::decode(const Edge* first, const Edge* last, std::uint64_t taken) {
    std::uint32_t dropped = 0;
    if (auto result = pieces_.takePieceResult(dropped))
        if (auto* s = dynamic_cast<Speculation*>(result.get())) {
            result.release();
            splicer_.startPiece(std::unique_ptr<Speculation>(s), taken, dropped);
        }
    return splicer_.decode(first, last, taken);
}

}  // namespace busdecode
