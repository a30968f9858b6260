// Where a BiSS-C decoder started partway through a capture may take over from the one
// that decoded everything before (core/piece_speculation.h): the state compared, and the
// totals carried across.
#include "bissc_decoder.h"
#include "core/splice_words.h"

namespace busdecode {

bool BisscDecoder::spliceState(SpliceState& out) const {
    // Between frames: a frame just begun by its first clock edge. The previous frame is
    // out (its event emitted) and only what it measured is carried on. (Not while idle: a
    // decoder started in the middle of a frame is idle for a while, long before it could
    // match, and would spend the splice points the speculator looks for.)
    if (c_.state != State::WaitAck || !f_.rises.empty() || !sampler_.empty()) return false;
    out.words.clear();
    out.counts.clear();
    if (!control_.appendSpliceWords(out.words)) return false;
    SpliceWords w(out.words);
    w.fields(c_) << busySince() << sampler_.level();
    // The frame: just begun (most fields still as beginFrame() left them), or the last one
    // when idle, which a new frame resets; compared whole either way, not reasoned about.
    w.fields(run_).fields(static_cast<const FrameFields&>(f_)) << f_.rises.size();
    for (std::size_t i = 0; i < f_.rises.size(); ++i)
        w << f_.rises[i];
    w << f_.errors.size();
    for (const auto& e : f_.errors)
        w << e;
    out.counts = {frames_,        answered_frames_, clean_frames_,
                  slow_ma_edges_, slow_sl_edges_,   skipped_frames_};
    return true;
}

void BisscDecoder::addCounts(const std::vector<std::uint64_t>& delta) {
    std::uint64_t* counts[] = {&frames_,        &answered_frames_, &clean_frames_,
                               &slow_ma_edges_, &slow_sl_edges_,   &skipped_frames_};
    for (std::size_t i = 0; i < delta.size() && i < std::size(counts); ++i)
        *counts[i] += delta[i];
}

}  // namespace busdecode
