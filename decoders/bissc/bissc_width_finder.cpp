#include "bissc_width_finder.h"

#include <string>

#include <fmt/format.h>

#include "bissc_decoder.h"
#include "bissc_options.h"

namespace busdecode {

namespace {

constexpr int kDefaultBits = BisscSettings{}.bits;  // the contract's default, when nothing fits
constexpr int kMaxBits = 64;

}  // namespace

BisscWidthFinder::BisscWidthFinder(const Options& options) : options_(options) {
    // Anything wrong besides the width is reported now, as with a fixed width: the check
    // a BisscDecoder makes, for the widest frame.
    Options widest = options_;
    widest.setRaw("bits", std::to_string(kMaxBits));
    (void)BisscSettings::from(widest);
}

BisscWidthFinder::~BisscWidthFinder() = default;

std::unique_ptr<BisscDecoder> BisscWidthFinder::makeDecoder(int bits) const {
    Options o = options_;
    o.setRaw("bits", std::to_string(bits));
    try {
        return std::make_unique<BisscDecoder>(o);
    } catch (const InputError&) {
        return nullptr;  // e.g. st_bits + mt_bits wider than this width
    }
}

void BisscWidthFinder::start(const DecoderContext& ctx) {
    Decoder::start(ctx);
    held_.clear();
    held_.reserve(kLearnEdges);
    last_advance_ = kNoTick;
    decoder_.reset();
    width_ = 0;
    found_ = false;
}

bool BisscWidthFinder::spanOver(Tick now) const {
    return !held_.empty() && double(now - held_.front().t) * tb().secondsPerTick() >= kLearnSeconds;
}

void BisscWidthFinder::hold(const Held& h) {
    held_.push_back(h);
    if (held_.size() >= kLearnEdges || spanOver(h.t)) {
        decide(score(kNoTick).best);
    } else if (held_.size() % kTryEvery == 0) {
        // Decided early when one width stands out (no other fits even a quarter as many
        // frames: a wrong width fits one frame in 128 by chance), so that a short capture
        // still being written (--follow) shows its frames before the learning span ends.
        const Scores s = score(kNoTick);
        if (s.best_clean >= kSureFrames && s.runner_up_clean * 4 <= s.best_clean) decide(s.best);
    }
}

void BisscWidthFinder::edge(Tick t, int role, bool level) {
    if (decoder_)
        decoder_->edge(t, role, level);
    else
        hold({t, role, level, false});
}

void BisscWidthFinder::edges(const Edge* first, const Edge* last, const int* role_of_line) {
    for (; first != last && !decoder_; ++first)
        hold({first->t, role_of_line[first->line], first->level != 0, false});
    if (first != last) decoder_->edges(first, last, role_of_line);  // the block loop
}

void BisscWidthFinder::glitch(Tick t, int role) {
    if (decoder_)
        decoder_->glitch(t, role);
    else
        hold({t, role, false, true});
}

void BisscWidthFinder::advance(Tick now) {
    if (decoder_) {
        decoder_->advance(now);
        return;
    }
    last_advance_ = now;
    // A live capture that goes quiet still gets its frames within kLearnSeconds.
    if (spanOver(now)) decide(score(kNoTick).best);
}

void BisscWidthFinder::finish(Tick end) {
    if (!decoder_) decide(score(end).best);
    decoder_->finish(end);
}

Tick BisscWidthFinder::watermark(Tick now) const {
    if (decoder_) return decoder_->watermark(now);
    // Every event still to come starts at a held edge or later.
    return held_.empty() ? now : std::min(now, held_.front().t);
}

void BisscWidthFinder::replay(Decoder& d, const std::vector<Held>& held) {
    for (const auto& h : held)
        if (h.glitch)
            d.glitch(h.t, h.role);
        else
            d.edge(h.t, h.role, h.level);
}

BisscWidthFinder::Scores BisscWidthFinder::score(Tick end) const {
    Scores out;
    const Tick last = held_.empty() ? ctx_.capture_start : held_.back().t;
    for (int bits = 1; bits <= kMaxBits; ++bits) {
        auto candidate = makeDecoder(bits);
        if (!candidate) continue;
        // Its events are not wanted (no sink: Decoder::emit drops them); it counts its
        // clean frames itself.
        DecoderContext ctx = ctx_;
        ctx.sink = nullptr;
        candidate->setHints({false, false});
        candidate->start(ctx);
        replay(*candidate, held_);
        // Mid-capture, only the frames that ended among the held edges count (the one in
        // progress is not over yet); at the end, every frame the capture holds.
        if (end != kNoTick)
            candidate->finish(end);
        else
            candidate->advance(last);
        const std::uint64_t clean = candidate->cleanFrames();
        if (clean > 0 && clean >= out.best_clean) {  // ties: the larger width
            if (out.best) out.runner_up_clean = std::max(out.runner_up_clean, out.best_clean);
            out.best = bits;
            out.best_clean = clean;
        } else {
            out.runner_up_clean = std::max(out.runner_up_clean, clean);
        }
    }
    return out;
}

void BisscWidthFinder::decide(int best) {
    found_ = best != 0;
    width_ = best ? best : kDefaultBits;
    decoder_ = makeDecoder(width_);
    if (!decoder_) {  // st_bits + mt_bits wider than the default: the widest frame
        width_ = kMaxBits;
        decoder_ = makeDecoder(width_);  // checked in the constructor
    }
    decoder_->setHints(hints());
    decoder_->start(ctx_);
    replay(*decoder_, held_);
    if (last_advance_ != kNoTick && (held_.empty() || last_advance_ > held_.back().t))
        decoder_->advance(last_advance_);
    held_.clear();
    held_.shrink_to_fit();
}

std::vector<std::string> BisscWidthFinder::advice() const {
    if (!decoder_ || found_) return decoder_ ? decoder_->advice() : std::vector<std::string>{};
    // No width fitted. Without an answered frame, the decoder's advice says why (lines
    // that never make a frame); with some, its width is the default, no guide to the width.
    if (decoder_->answeredFrames() == 0) return decoder_->advice();
    return {fmt::format(
        "no data width from 1 to {} gives a clean frame (CRC right, stop bit low; {} answered "
        "frames decoded with the default, bits={}): check that MA and SL are not swapped, and "
        "the CRC options",
        kMaxBits, decoder_->answeredFrames(), width_)};
}

}  // namespace busdecode
