#pragma once
// The decoder interface. A decoder is a plain C++ state machine fed with the edges of
// its bound lines in time order (merged next-edge iteration, as in libscopehal): cost
// grows with edges, not samples. No Qt in here. CONTRIBUTING.md shows how to add one.
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "decoder_info.h"
#include "edge.h"
#include "event.h"
#include "options.h"
#include "time.h"

namespace busdecode {

class EventWindow;

struct DecoderContext {
    Timebase timebase;
    // Initial level of each role, in DecoderInfo::roles order; -1 when the role is unbound.
    std::vector<int> initial_levels;
    EventSink* sink = nullptr;
    Tick capture_start = 0;  // first tick of the capture (may be negative)
};

// What a decoder implements. Edges arrive one at a time through edge(); a decoder on
// the hot path may also take whole blocks (core/block_decoding.h) and be spliced for
// piece-parallel decoding (core/splicing.h), but none has to.
class Decoder {
public:
    Decoder() = default;
    // `proto`: the decoder's id, which newEvent() puts in every event (a literal).
    explicit Decoder(std::string_view proto) : proto_(proto) {}
    virtual ~Decoder() = default;

    // Called once before any edge.
    virtual void start(const DecoderContext& ctx) { ctx_ = ctx; }
    // A level change on role `role` (index into DecoderInfo::roles) at tick t.
    virtual void edge(Tick t, int role, bool level) = 0;
    // Time has advanced to `now` with no further edge on this decoder's lines before it.
    // Called between edge blocks; lets timeouts close frames promptly in live decoding.
    virtual void advance(Tick now) { (void)now; }
    // End of capture at tick `end`: flush or report what is still open (short_frame).
    virtual void finish(Tick end) = 0;
    // The glitch filter removed a pulse shorter than glitch_ns on `role` at tick t.
    virtual void glitch(Tick t, int role) {
        (void)t;
        (void)role;
    }
    // Cross-decoder correlation: the session calls this for every event this decoder
    // emitted with `correlate` requested (see requestCorrelation), once events from all
    // other decoders up to the event's end are known. `window` holds them by time.
    virtual void correlate(Event& e, const EventWindow& window) {
        (void)e;
        (void)window;
    }
    // True if this decoder may set Event::wants_correlation. The session keeps the
    // window of recent events (a copy of each) only when some decoder says so.
    virtual bool correlates() const { return false; }
    // After finish(): advice on the capture as a whole, one line each, for whoever reads
    // the output (an option that looks wrong, say). Not events: the events say what the
    // traffic holds, this what to try next.
    virtual std::vector<std::string> advice() const { return {}; }

    // The earliest start tick of any event this decoder may still emit. The session
    // releases events in time order up to the minimum over all decoders.
    // Stacked decoders override it to include their lower decoder's.
    virtual Tick watermark(Tick now) const { return busy_since_ == kNoTick ? now : busy_since_; }

    // Events this decoder emits go to `sink`.
    void setSink(EventSink* sink) { ctx_.sink = sink; }
    const DecoderContext& context() const { return ctx_; }

protected:
    // An event of this decoder's proto and `type` from `start` to `end`, to fill and
    // emit(); its storage recycled by the sink where it can be.
    EventPtr newEvent(std::string_view type, Tick start, Tick end) {
        EventPtr e = ctx_.sink ? ctx_.sink->freshEvent() : std::make_unique<Event>();
        e->proto.assign(proto_);
        e->type.assign(type);
        e->start = start;
        e->end = end;
        return e;
    }
    void emit(EventPtr e) {
        if (ctx_.sink) ctx_.sink->onOwnedEvent(std::move(e));
    }
    void emit(Event&& e) {
        if (ctx_.sink) ctx_.sink->onEvent(std::move(e));
    }
    // Call when a frame (or anything that will become an event) starts / is done.
    void busyFrom(Tick t) {
        if (busy_since_ == kNoTick || t < busy_since_) busy_since_ = t;
    }
    void setBusyFrom(Tick t) { busy_since_ = t; }
    void idle() { busy_since_ = kNoTick; }
    // The earliest start of an event still to come, or kNoTick.
    Tick busySince() const { return busy_since_; }
    const Timebase& tb() const { return ctx_.timebase; }

    DecoderContext ctx_;

private:
    std::string_view proto_;
    Tick busy_since_ = kNoTick;
};

class DecoderFactory {
public:
    virtual ~DecoderFactory() = default;
    virtual const DecoderInfo& info() const = 0;
    virtual std::unique_ptr<Decoder> create(const Options& options) const = 0;
};

}  // namespace busdecode
