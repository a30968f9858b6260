#include "piece_speculation.h"

#include <algorithm>
#include <limits>
#include <utility>

namespace busdecode {

namespace {

// Keeps a speculative decoder's events aside, filled in storage from this thread's pool
// (the session's own store of recycled events belongs to the decoding thread), marked
// with `home`, the pool the session gives them back to.
class KeepEvents final : public EventSink {
public:
    KeepEvents(std::vector<EventPtr>& events, EventPool* pool, std::uint8_t home,
               const std::string& instance)
        : events_(events), store_(0, pool), home_(home), instance_(instance) {}
    void onEvent(Event&& e) override { onOwnedEvent(store_.adopt(std::move(e))); }
    void onOwnedEvent(EventPtr e) override {
        EventHome::set(*e, home_);
        e->instance = instance_;
        events_.push_back(std::move(e));
    }
    EventPtr freshEvent() override { return store_.fresh(); }

private:
    std::vector<EventPtr>& events_;
    RecycledEvents store_;
    const std::uint8_t home_;
    const std::string& instance_;
};

// Tells an edge that follows a pause: a gap since the edge before it more than kPauseGaps
// times the shortest gap (above zero) seen so far.
class Pauses {
public:
    bool after(Tick t) {
        const Tick gap = last_ == kNoTick ? 0 : t - last_;
        last_ = t;
        if (gap > 0 && gap < shortest_) shortest_ = gap;
        return gap > PieceSpeculator::kPauseGaps * shortest_;
    }

private:
    Tick last_ = kNoTick;
    Tick shortest_ = std::numeric_limits<Tick>::max() / PieceSpeculator::kPauseGaps;
};

}  // namespace

PieceSpeculator::PieceSpeculator(const DecoderFactory& factory, Options options, DecoderContext ctx,
                                 FastPathHints hints, std::vector<int> role_of_line,
                                 std::shared_ptr<EventPool> decoding_pool,
                                 std::shared_ptr<EventPool> other_pool, std::string instance)
    : factory_(factory),
      options_(std::move(options)),
      ctx_(std::move(ctx)),
      hints_(hints),
      role_of_line_(std::move(role_of_line)),
      decoding_pool_(std::move(decoding_pool)),
      other_pool_(std::move(other_pool)),
      instance_(std::move(instance)) {}

std::unique_ptr<PieceWork::Result> PieceSpeculator::run(const Piece& piece) {
    // Every line's first edge in the piece may repeat the level it had before (the reader
    // then drops it), and that level is not known here. So the fresh decoder starts
    // after every line's first edge, at the first pause in the traffic (where a frame
    // starts), with the levels the edges before it left: it sees exactly the edges the
    // decoding thread will, from there on, and none from the middle of a frame.
    const std::size_t lines = role_of_line_.size();
    std::uint64_t stable_from = 0;  // edges taken once every line's first one is
    for (std::size_t line = 0; line < lines; ++line) {
        if (role_of_line_[line] < 0) continue;
        const std::uint32_t at =
            line < piece.first_edge->size() ? (*piece.first_edge)[line] : PieceWork::kNoEdge;
        if (at == PieceWork::kNoEdge) return nullptr;  // a level not known at all
        stable_from = std::max<std::uint64_t>(stable_from, std::uint64_t(at) + 1);
    }
    // One pass over the piece: until the decoder starts, the levels each edge leaves;
    // from then on, the blocks handed over in runs that end where a splice point may be
    // (the decoder's state is only known between its calls): at an edge after a pause,
    // the first kSnapshots such edges where the decoder has a SpliceState. After each
    // block, advance() to its last edge, as the session does.
    auto spec = std::make_unique<Speculation>();
    // On the decoding thread, the session's pool and home 0; on the other, that one's.
    const bool other = piece.thread != 0 && other_pool_;
    KeepEvents keep(spec->events, other ? other_pool_.get() : decoding_pool_.get(),
                    std::uint8_t(other ? 1 : 0), instance_);
    FastDecoder* d = nullptr;
    SpliceableDecoder* splicing = nullptr;
    std::vector<int> level(lines, -1);
    Pauses pauses;
    SpliceState state;
    const int* roles = role_of_line_.data();
    std::uint64_t taken = 0;  // edges of the blocks before this one
    Tick now = kNoTick;
    std::uint64_t pause_count = 0;
    for (std::size_t b = 0; b < piece.used; ++b) {
        const auto& edges = piece.blocks[b].edges;
        const Edge* e = edges.data();
        const std::size_t n = edges.size();
        std::size_t i = 0;  // edges [.., i) handed over (or, before the start, passed)
        for (std::size_t j = 0; j < n && (!d || spec->snapshots.size() < kSnapshots); ++j) {
            const bool pause = pauses.after(e[j].t);
            if (!d) {
                if (!pause || taken + j < stable_from) {
                    level[e[j].line] = e[j].level;
                    continue;
                }
                d = startDecoder(*spec, keep, level);
                if (!d) return nullptr;
                splicing = splicingOf(*d);
                i = j;
            } else if (!pause) {
                continue;
            }
            // The first few pauses, then every kSparseEvery-th: a state that meets the
            // other's late still finds a splice point, at little cost.
            if (++pause_count > kDenseSnapshots && pause_count % kSparseEvery != 0) continue;
            d->edges(e + i, e + j + 1, roles);
            i = j + 1;
            if (splicing->spliceState(state)) {
                spec->snapshots.push_back({taken + i, spec->events.size(), std::move(state)});
                state = SpliceState{};
            }
        }
        taken += n;
        if (!d) continue;
        d->edges(e + i, e + n, roles);
        if (n == 0) continue;  // the session never sees an empty block
        now = now == kNoTick ? edges.back().t : std::max(now, edges.back().t);
        d->advance(now);
    }
    spec->edges = taken;
    spec->last = now;
    if (spec->snapshots.empty()) return nullptr;  // no pause: no frame starts in the piece
    return spec;
}

FastDecoder* PieceSpeculator::startDecoder(Speculation& spec, EventSink& sink,
                                           const std::vector<int>& level_of_line) const {
    DecoderContext ctx = ctx_;
    for (std::size_t line = 0; line < role_of_line_.size(); ++line) {
        const int role = role_of_line_[line];
        if (role >= 0 && std::size_t(role) < ctx.initial_levels.size())
            ctx.initial_levels[std::size_t(role)] = level_of_line[line];
    }
    ctx.sink = &sink;
    spec.decoder = factory_.create(options_);
    FastDecoder* fast = fastPathOf(*spec.decoder);
    SpliceableDecoder* splicing = splicingOf(*spec.decoder);
    if (!fast || !splicing) return nullptr;
    fast->setHints(hints_);
    spec.decoder->start(ctx);
    splicing->guessHistory();
    spec.decoder->setSink(&sink);
    return fast;
}

void SpeculationSplicer::startPiece(std::unique_ptr<Speculation> s, std::uint64_t taken,
                                    std::uint32_t dropped) {
    ++stats_.pieces;
    spec_ = std::move(s);
    base_ = taken - dropped;  // modulo 2^64: every snapshot lies at or past `taken`
    next_ = 0;
}

bool SpeculationSplicer::decode(const Edge* first, const Edge* last, std::uint64_t taken) {
    const std::uint64_t n = std::uint64_t(last - first);
    if (taken < skip_until_) return false;  // (blocks never straddle pieces)
    std::uint64_t done = 0;                 // of this block
    while (spec_ && next_ < spec_->snapshots.size()) {
        Speculation::Snapshot& at = spec_->snapshots[next_];
        const std::uint64_t pos = base_ + at.after;  // in edges handed out
        if (pos > taken + n) break;                  // in a later block
        ++next_;
        if (pos < taken + done) continue;  // (cannot be: each lies past the one before)
        fast_->edges(first + done, first + (pos - taken), role_of_line_);
        done = pos - taken;
        SpliceState mine;
        if (splicing_->spliceState(mine) && mine.words == at.state.words) {
            skip_until_ = base_ + spec_->edges;
            decoded_until_ = spec_->last;
            stats_.edges_ahead += skip_until_ - pos;
            splice(at, mine);
            return false;
        }
    }
    if (spec_ && next_ == spec_->snapshots.size()) spec_.reset();  // no splice: decode on
    fast_->edges(first + done, last, role_of_line_);
    return true;
}

void SpeculationSplicer::splice(Speculation::Snapshot& at, const SpliceState& mine) {
    ++stats_.spliced;
    std::vector<std::uint64_t> delta(mine.counts.size());
    for (std::size_t i = 0; i < delta.size() && i < at.state.counts.size(); ++i)
        delta[i] = mine.counts[i] - at.state.counts[i];
    std::unique_ptr<Decoder> next = std::move(spec_->decoder);
    splicingOf(*next)->addCounts(delta);
    next->setSink(&sink_);
    for (std::size_t i = at.events; i < spec_->events.size(); ++i)
        sink_.onOwnedEvent(std::move(spec_->events[i]));
    decoder_ = std::move(next);
    spec_.reset();
    lookUpDecoder();
}

void SpeculationSplicer::lookUpDecoder() {
    fast_ = fastPathOf(*decoder_);
    splicing_ = splicingOf(*decoder_);
}

}  // namespace busdecode
