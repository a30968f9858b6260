#pragma once
// The decoder interface. A decoder is a plain C++ state machine fed with the edges of
// its bound lines in time order (merged next-edge iteration, as in libscopehal): cost
// grows with edges, not samples. No Qt in here.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "decoder_info.h"
#include "edge.h"
#include "event.h"
#include "options.h"
#include "time.h"

namespace busdecode {

class EventWindow;

// What a decoder is at one point of the edge stream, for decoding a capture in pieces on
// several threads at once (core/piece_speculation.h): a decoder started fresh partway
// through the capture takes over from the one that decoded up to there, from the first
// point where their states are the same. `words` is everything that decides what the
// decoder does with the edges after that point; two decoders with the same words there
// emit the same events from then on. `counts` are running totals (frames seen, say)
// that do not decide anything: the one taking over adds the other's (addCounts()).
struct SpliceState {
    std::vector<std::uint64_t> words;
    std::vector<std::uint64_t> counts;
};

struct DecoderContext {
    Timebase timebase;
    // Initial level of each role, in DecoderInfo::roles order; -1 when the role is unbound.
    std::vector<int> initial_levels;
    EventSink* sink = nullptr;
    Tick capture_start = 0;  // first tick of the capture (may be negative)
    // False when nothing reads the events' fields: only text output, which prints the
    // summary, and no decoder correlating or stacked on this one. A decoder whose events
    // always carry a summary may then leave its fields out (a BiSS-C frame's 20 fields
    // are a tenth of decode's time on a busy bus).
    bool fields_wanted = true;
    // Every edge handed to edges() has its role for its line (role_of_line maps each line
    // that carries edges to itself): a decoder may take the role from Edge::line and skip
    // the look-up, which sits on the way to the branch on the role (mispredicted at
    // random where the data is random: BiSS-C's `decode/bissc` micro-benchmark 3-4 %
    // faster without it). The session's usual case: one
    // decoder, its roles bound in order.
    bool lines_are_roles = false;
};

// Whether role_of_line maps every line that carries edges (those with a role, >= 0) to
// itself: DecoderContext::lines_are_roles for edges() handed that table.
inline bool linesAreRoles(const std::vector<int>& role_of_line) {
    for (std::size_t line = 0; line < role_of_line.size(); ++line)
        if (role_of_line[line] >= 0 && role_of_line[line] != int(line)) return false;
    return true;
}

class Decoder {
public:
    virtual ~Decoder() = default;

    // Called once before any edge.
    virtual void start(const DecoderContext& ctx) { ctx_ = ctx; }
    // A level change on role `role` (index into DecoderInfo::roles) at tick t.
    virtual void edge(Tick t, int role, bool level) = 0;
    // A run of edges in time order, none repeating its line's level; role_of_line maps
    // Edge::line to the role. The session hands over whole blocks this way when this is
    // the only decoder and no glitch filter sits in between. BlockDecoder below inlines
    // the decoder's edge() into the loop; this fallback makes one virtual call per edge.
    virtual void edges(const Edge* first, const Edge* last, const int* role_of_line) {
        for (; first != last; ++first)
            edge(first->t, role_of_line[first->line], first->level != 0);
    }
    // One edge through the decoder's general code alone: what edge() does, without the
    // fast paths a decoder may take in edge() or edges(). Such a decoder overrides it,
    // and its tests and the fuzz harness check the fast paths against it.
    virtual void edgeReference(Tick t, int role, bool level) { edge(t, role, level); }
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

    // Piece-parallel decoding (core/piece_speculation.h). A decoder that can be spliced
    // says so here, and fills `out` in spliceState() wherever it is at a point it can be
    // compared at (between frames, say), returning false elsewhere: a false costs
    // nothing but a later splice. Every field it leaves out of SpliceState::words must
    // be one that two decoders of the same options given the same edges from that point
    // on cannot differ in.
    virtual bool splices() const { return false; }
    virtual bool spliceState(SpliceState& out) const {
        (void)out;
        return false;
    }
    // Called after start() on a decoder started partway through the capture: it may set
    // what it cannot know to what a long capture most likely left (BiSS-C: a preamble of
    // CDM zeros seen), so that its state meets the other's sooner. A wrong guess costs a
    // later splice, never a different output.
    virtual void guessHistory() {}
    // Adds `delta` to SpliceState::counts, element by element (modulo 2^64): this
    // decoder takes over from one whose totals were that much higher.
    virtual void addCounts(const std::vector<std::uint64_t>& delta) { (void)delta; }

    // Events this decoder emits go to `sink`.
    void setSink(EventSink* sink) { ctx_.sink = sink; }
    const DecoderContext& context() const { return ctx_; }

protected:
    void emit(Event&& e) {
        if (ctx_.sink) ctx_.sink->onEvent(std::move(e));
    }
    // An event from freshEvent(), handed over by its pointer.
    void emit(EventPtr e) {
        if (ctx_.sink) ctx_.sink->onOwnedEvent(std::move(e));
    }
    // The event to fill for emit(): empty, with storage recycled by the sink if it can.
    EventPtr freshEvent() {
        return ctx_.sink ? ctx_.sink->freshEvent() : std::make_unique<Event>();
    }
    // Call when a frame (or anything that will become an event) starts / is done.
    void busyFrom(Tick t) {
        if (busy_since_ == kNoTick || t < busy_since_) busy_since_ = t;
    }
    void setBusyFrom(Tick t) { busy_since_ = t; }
    void idle() { busy_since_ = kNoTick; }
    // For spliceState(): the earliest start of an event still to come, or kNoTick.
    Tick busySince() const { return busy_since_; }
    const Timebase& tb() const { return ctx_.timebase; }
    // Whether to add fields to the events (DecoderContext::fields_wanted).
    bool fieldsWanted() const { return ctx_.fields_wanted; }

    DecoderContext ctx_;

private:
    Tick busy_since_ = kNoTick;
};

// Base for decoders: the block loop calls Derived::edge directly (no virtual call per
// edge), so the compiler can inline the decoder's edge handling into it.
template <class Derived>
class BlockDecoder : public Decoder {
public:
    void edges(const Edge* first, const Edge* last, const int* role_of_line) final {
        Derived& d = static_cast<Derived&>(*this);
        for (; first != last; ++first)
            d.Derived::edge(first->t, role_of_line[first->line], first->level != 0);
    }
};

class DecoderFactory {
public:
    virtual ~DecoderFactory() = default;
    virtual const DecoderInfo& info() const = 0;
    virtual std::unique_ptr<Decoder> create(const Options& options) const = 0;
};

}  // namespace busdecode
