#include "session.h"

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cmath>
#include <deque>
#include <numeric>
#include <optional>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "block_decoding.h"
#include "capture/vector_range.h"
#include "edit_distance.h"
#include "event_pool.h"
#include "event_window.h"
#include "glitch_filter.h"
#include "interrupted.h"
#include "parallel_pipeline.h"
#include "registry.h"
#include "splicing.h"
#include "waveform.h"

namespace busdecode {

namespace {

std::string lower(std::string s) {
    for (auto& c : s)
        c = char(std::tolower((unsigned char)c));
    return s;
}

// Resolves a user's signal reference: full hierarchical name, last component, a CSV
// column index, or `name[bit]` for one bit of a vector.
// A one-bit signal declared with a bit-select (VCD "$var wire 1 ! tx [0] $end", named
// "tx[0]"), found by its base name alone when no other signal has that base.
template <class Eq>
std::optional<LineRef> oneBitDeclaredWithItsIndex(const std::vector<SignalInfo>& sigs,
                                                  const std::string& ref, const Eq& eq) {
    if (ref.find('[') != std::string::npos) return std::nullopt;
    std::optional<LineRef> only;
    for (int i = 0; i < int(sigs.size()); ++i) {
        const std::string& n = sigs[i].name;
        const auto lb = n.rfind('[');
        if (sigs[i].width != 1 || lb == std::string::npos || n.back() != ']' ||
            !eq(n.substr(0, lb), ref))
            continue;
        if (only) return std::nullopt;  // data[0] and data[1]: the user names which
        only = LineRef{i, -1};
    }
    return only;
}

std::optional<LineRef> findSignal(const std::vector<SignalInfo>& sigs, const std::string& ref,
                                  bool case_insensitive) {
    auto eq = [&](const std::string& a, const std::string& b) {
        return case_insensitive ? lower(a) == lower(b) : a == b;
    };
    for (int i = 0; i < int(sigs.size()); ++i)
        if (eq(sigs[i].full_name, ref)) return LineRef{i, -1};
    for (int i = 0; i < int(sigs.size()); ++i)
        if (eq(sigs[i].name, ref)) return LineRef{i, -1};
    // name[bit] selects one bit of a vector
    auto lb = ref.rfind('[');
    if (lb != std::string::npos && ref.back() == ']') {
        auto index = parseInteger(ref.substr(lb + 1, ref.size() - lb - 2));
        auto base = findSignal(sigs, ref.substr(0, lb), case_insensitive);
        if (index && base)
            if (const auto bit = bitAtIndex(sigs[base->signal], *index))
                return LineRef{base->signal, *bit};
    }
    if (auto only = oneBitDeclaredWithItsIndex(sigs, ref, eq)) return only;
    if (!case_insensitive) {
        if (auto idx = parseInteger(ref); idx && *idx >= 0 && *idx < std::int64_t(sigs.size()))
            return LineRef{int(*idx), -1};
    }
    return std::nullopt;
}

// The capture's signals for a message: all of a short list; of a long one (a simulator's
// VCD may declare 10^5), the few closest to `wanted` and how many there are.
std::string signalList(const CaptureReader& reader, const std::string& wanted) {
    constexpr std::size_t kAll = 24, kClosest = 8;
    const std::vector<SignalInfo>& sigs = reader.signals();
    // None kept: a huge VCD header keeps only what --map and the roles name, and its
    // note says how many it declared.
    if (sigs.empty() && !reader.notes().empty())
        return fmt::format("none kept: {}", fmt::join(reader.notes(), "; "));
    std::vector<std::string> names;
    if (sigs.size() <= kAll) {
        for (const auto& s : sigs)
            if (!s.name.empty())
                names.push_back(signalText(s));  // unnamed: a live line not acquired
        return names.empty() ? "none" : fmt::format("{}", fmt::join(names, ", "));
    }
    std::vector<std::pair<std::size_t, std::size_t>> by_distance;  // (distance, index)
    by_distance.reserve(sigs.size());
    for (std::size_t i = 0; i < sigs.size(); ++i)
        if (!sigs[i].name.empty())
            by_distance.emplace_back(std::min(editDistance(sigs[i].name, wanted),
                                              editDistance(sigs[i].full_name, wanted)),
                                     i);
    const std::size_t closest = std::min(kClosest, by_distance.size());
    std::partial_sort(by_distance.begin(), by_distance.begin() + std::ptrdiff_t(closest),
                      by_distance.end());
    for (std::size_t k = 0; k < closest; ++k)
        names.push_back(signalText(sigs[by_distance[k].second]));
    return fmt::format("{} in all; the closest: {}", by_distance.size(), fmt::join(names, ", "));
}

OptionSpec glitchOption() {
    // At most one second: wider is no glitch, and its ticks must fit an Edge's time.
    return numberOption("glitch_ns", "0", 0, 1e9,
                        "ignore pulses shorter than this on every mapped line (ns)");
}

}  // namespace

std::pair<std::string, std::string> splitScopedKey(const std::string& key) {
    auto dot = key.find('.');
    if (dot == std::string::npos) return {"", key};
    return {key.substr(0, dot), key.substr(dot + 1)};
}

struct Session::Impl : EventSink {
    struct Slot {
        std::string instance;
        std::unique_ptr<Decoder> decoder;
        const DecoderFactory* factory = nullptr;  // what made it, with these options
        Options options;
        std::vector<int> role_line;  // role index -> selected line, -1 unbound
        std::optional<GlitchFilter> glitch;
        DecoderContext ctx;
        FastDecoder* fast = nullptr;  // the decoder's fast path (block_decoding.h), if any
        FastPathHints hints;
    };
    // Where a selected line's edges go; the decoder and its glitch filter (or null) are
    // resolved once here, not per edge.
    struct Target {
        int slot;
        int role;
        Decoder* decoder;
        GlitchFilter* glitch;
    };

    CaptureReader* reader = nullptr;
    std::vector<Slot> slots;
    std::vector<LineRef> lines;
    std::vector<std::vector<Target>> targets;  // per selected line
    std::vector<std::uint8_t> levels;
    // Events not yet output, in start order, and which slot emitted each (two deques
    // kept in step, so the correlation window can see the events without a copy).
    std::deque<EventPtr> pending;
    std::deque<int> pending_slot;
    EventWindow window;
    bool keep_window = false;  // some decoder correlates: remember released events
    // One decoder, no glitch filter, one role per line: blocks go to the decoder whole.
    bool block_path = false;
    std::vector<int> role_of_line;
    int emitting = -1;
    Tick now = 0;
    bool speculate = true;
    Session::PieceStats piece_stats;
    std::atomic<bool> stop{false};
    const std::atomic<bool>* external_stop = nullptr;
    bool abandon_when_stopped = false;
    bool stopped() const { return stop || (external_stop && *external_stop); }
    std::vector<OutputSink*>* sinks = nullptr;
    CaptureFacts* facts = nullptr;
    // Output events, emptied, for decoders to fill again: their field vectors and
    // summaries keep their storage (two allocations and frees per event otherwise,
    // a quarter of an SPI word's cost by callgrind). Events are released once per edge
    // block, so the pool must hold a block's worth to serve the next one: 10 MHz BiSS-C
    // makes about 165 frames per block, of 100 edges each; with 64, two thirds of its
    // frames were built in new storage. At most about 2 MB. With pieces decoded ahead
    // (piece_speculation.h), most events are built on the reader's threads: what this
    // store cannot hold goes back to them through the shared pool.
    static constexpr std::size_t kMaxSpare = 1024;
    // The parallel path, where it runs (declared first: `spare` gives back to its pools).
    std::unique_ptr<ParallelVcdPipeline> parallel;
    RecycledEvents spare{kMaxSpare};

    EventPtr freshEvent() override { return spare.fresh(); }

    // An event a decoder built without freshEvent(): into storage of the pool.
    void onEvent(Event&& e) override { onOwnedEvent(spare.adopt(std::move(e))); }

    void onOwnedEvent(EventPtr e) override {
        // Compared first: an event filled on the other reader thread has it already
        // (PieceSpeculator), and writing it here would pull the event's storage to this
        // core, from which that thread must pull it back (bench/README.md, "Two dies").
        if (e->instance != slots[emitting].instance) e->instance = slots[emitting].instance;
        insertPending(std::move(e), emitting);
    }

    // `slot` -1: a finding of the capture layer (EdgeBlock::findings), not a decoder's.
    void insertPending(EventPtr e, int slot) {
        const Tick start = e->start;
        if (pending.empty() || pending.back()->start <= start) {  // the rule: in order
            pending.push_back(std::move(e));
            pending_slot.push_back(slot);
            return;
        }
        // Insert keeping start order (out-of-order events are late by a few: search from
        // the back).
        std::size_t at = pending.size();
        while (at > 0 && pending[at - 1]->start > start)
            --at;
        pending.insert(pending.begin() + at, std::move(e));
        pending_slot.insert(pending_slot.begin() + at, slot);
    }

    // A stretch the capture layer found (a finding that carries an error: a pair fault, a
    // line's no data, a live run's dropped samples, a sequence capture's dead time): the
    // events reaching into it of the slots it concerns are marked with that error. One that
    // names its signal (field `pair` or `line`) concerns the slots decoding from it alone.
    struct FaultSpan {
        Tick start, end;
        std::vector<int> slots;
        std::string error;
        std::string signal;  // the one signal it is about; "": every line of the slots
    };
    std::deque<FaultSpan> fault_spans;
    Tick findings_from = kNoTick;
    // Set at the capture's end: a decoded event cut by it (short_frame) was seen.
    Tick cut_from = std::numeric_limits<Tick>::max();
    bool cut_at_end = false;

    void takeFindings(EdgeBlock& block) {
        findings_from = block.findings_from;
        for (Event& f : block.findings) {
            if (!f.errors.empty()) {
                const char* key = f.has("pair") ? "pair" : f.has("line") ? "line" : nullptr;
                fault_spans.push_back({f.start, f.end, key ? slotsOf(f, key) : allSlots(),
                                       f.errors.front(), key ? textOf(f, key) : ""});
            }
            f.instance = f.proto;
            insertPending(spare.adopt(std::move(f)), -1);
        }
        block.findings.clear();
    }
    // The slots decoding from the signal that the finding's field `key` names.
    std::vector<int> slotsOf(const Event& fault, const char* key) const {
        std::vector<int> out;
        const Value* signal = fault.get(key);
        for (const auto& b : facts->bindings)
            for (int s = 0; s < int(slots.size()); ++s)
                if (signal && slots[s].instance == b.instance &&
                    std::get<std::string>(*signal) == b.signal)
                    out.push_back(s);
        return out;
    }
    static std::string textOf(const Event& e, const char* key) {
        const Value* v = e.get(key);
        const auto* text = v ? std::get_if<std::string>(v) : nullptr;
        return text ? *text : std::string();
    }
    // False when the event names its line (field `line`: a role, as UART's bytes do) and
    // that role of the slot's decoder reads another signal than `signal`.
    bool mayReadFrom(const Event& e, int slot, const std::string& signal) const {
        const std::string role = textOf(e, "line");
        if (role.empty()) return true;
        for (const auto& b : facts->bindings)
            if (b.instance == slots[slot].instance && b.role == role) return b.signal == signal;
        return true;
    }
    std::vector<int> allSlots() const {
        std::vector<int> out(slots.size());
        std::iota(out.begin(), out.end(), 0);
        return out;
    }
    // Events go out in start order: spans ending before this one's start are done.
    void markFaultSpans(Event& e, int slot) {
        while (!fault_spans.empty() && fault_spans.front().end < e.start)
            fault_spans.pop_front();
        for (const auto& f : fault_spans)
            if (f.start <= e.end && e.start <= f.end &&
                std::find(f.slots.begin(), f.slots.end(), slot) != f.slots.end() &&
                (f.signal.empty() || mayReadFrom(e, slot, f.signal)))
                e.error(f.error);
    }

    Tick watermark() const {
        Tick w = findings_from == kNoTick ? now : std::min(now, findings_from);
        for (const auto& s : slots) {
            w = std::min(w, s.decoder->watermark(now));
            if (s.glitch && s.glitch->oldest() != kNoTick) w = std::min(w, s.glitch->oldest());
        }
        return w;
    }

    // Outputs e, taken out of `pending`, then keeps it for reuse or in the correlation
    // window.
    void output(EventPtr e, int slot) {
        if (slot >= 0 && e->wants_correlation) {
            window.setPending(&pending);
            slots[slot].decoder->correlate(*e, window);
            window.setPending(nullptr);
        }
        if (slot >= 0 && !fault_spans.empty()) markFaultSpans(*e, slot);
        if (slot >= 0 && e->end >= cut_from && e->hasError("short_frame")) cut_at_end = true;
        for (auto* s : *sinks)
            s->onEvent(*e, *facts);
        if (keep_window && slot >= 0) {
            window.remember(std::move(e), 4096);
        } else {
            spare.recycle(std::move(e));
        }
    }

    void release(bool all) {
        const Tick w = all ? std::numeric_limits<Tick>::max() : watermark();
        constexpr std::size_t kMaxHeld = 200000;  // bounded memory even if a decoder stalls
        while (!pending.empty()) {
            const Event& next = *pending.front();
            const bool forced = pending.size() > kMaxHeld;
            if (!all && !forced) {
                if (next.start >= w) break;
                if (next.wants_correlation && next.end >= w) break;
                // One reaching into a pair fault still open waits to be marked.
                if (findings_from != kNoTick && next.end >= findings_from) break;
            }
            // Out of `pending` first: the correlation window shows what is still pending.
            EventPtr out = std::move(pending.front());
            const int slot = pending_slot.front();
            pending.pop_front();
            pending_slot.pop_front();
            output(std::move(out), slot);
        }
    }

    // What a glitch filter lets through, handed to its decoder: pulses it removed as
    // glitch(), the rest as edge().
    static auto filtered(Decoder& d) {
        return [&d](const GlitchFilter::Out& o) {
            if (o.is_glitch)
                d.glitch(o.t, o.role);
            else
                d.edge(o.t, o.role, o.level);
        };
    }

    void deliver(const Target& tg, Tick t, bool level) {
        emitting = tg.slot;
        if (!tg.glitch)
            tg.decoder->edge(t, tg.role, level);
        else
            deliverFiltered(tg, t, level);
    }
    // Kept out of the per-edge loop: the filter's code would crowd the common path.
    [[gnu::noinline]] void deliverFiltered(const Target& tg, Tick t, bool level) {
        tg.glitch->push(t, tg.role, level, filtered(*tg.decoder));
    }

    // A decoder for `req` (its glitch_ns taken out of the options), not yet bound.
    Slot makeSlot(DecoderRequest& req, std::string instance) {
        const DecoderFactory* f = Registry::instance().find(req.proto);
        if (!f) Registry::instance().create(req.proto, {});  // throws the "unknown decoder" error
        const DecoderInfo& info = f->info();
        Slot slot;
        slot.instance = std::move(instance);
        // glitch_ns is handled here for every decoder.
        double glitch_ns = 0;
        if (auto it = req.options.find("glitch_ns"); it != req.options.end()) {
            DecoderInfo gi;
            gi.id = info.id;
            gi.options = {glitchOption()};
            glitch_ns = Options::resolve(gi, {{"glitch_ns", it->second}}).number("glitch_ns");
            req.options.erase(it);
        }
        slot.options = Options::resolve(info, req.options);
        slot.factory = f;
        slot.decoder = f->create(slot.options);
        if (glitch_ns > 0) {
            const double ticks = reader->timebase().fromNs(glitch_ns);
            if (!(ticks < double(kMaxEdgeTick)))
                throw InputError(fmt::format(
                    "decoder {}: option glitch_ns={}: more ticks than a capture time holds",
                    info.id, glitch_ns));
            Tick w = Tick(std::llround(ticks));
            if (w > 0) slot.glitch.emplace(w);
        }
        return slot;
    }

    // Binds each of the slot's roles to a line: as --map says, else by name or alias.
    void bindRoles(Slot& slot, const std::map<std::string, std::string>& map) {
        const DecoderInfo& info = slot.factory->info();
        checkRolesKnown(info, map);
        std::vector<LineRef> bound_refs;
        for (const auto& rs : info.roles) {
            std::optional<LineRef> ref = findRole(info, rs, map, bound_refs);
            if (!ref) {
                slot.role_line.push_back(-1);
                if (rs.required)
                    throw InputError(fmt::format(
                        "{}: decoder {}: role '{}' is not bound: use --map {}=SIGNAL (signals: {})",
                        facts->file, info.id, rs.name, rs.name, signalList(*reader, rs.name)));
                continue;
            }
            bound_refs.push_back(*ref);
            slot.role_line.push_back(lineOf(*ref));
            std::string sname = reader->signals()[ref->signal].full_name;
            if (ref->bit >= 0) sname += fmt::format("[{}]", ref->bit);
            facts->bindings.push_back(
                {info.id, slot.instance, rs.name, sname, slot.role_line.back()});
        }
        checkOneOfBound(info, slot.role_line);
    }

    void checkRolesKnown(const DecoderInfo& info, const std::map<std::string, std::string>& map) {
        for (const auto& [role, _] : map) {
            bool known = false;
            for (const auto& rs : info.roles)
                known |= rs.name == role;
            if (known) continue;
            std::vector<std::string> roles;
            for (const auto& rs : info.roles)
                roles.push_back(rs.name);
            throw InputError(fmt::format("decoder {}: unknown role '{}' in --map (roles: {})",
                                         info.id, role, fmt::join(roles, ", ")));
        }
    }

    // The signal for role `rs`, or none (throws where --map names no signal).
    std::optional<LineRef> findRole(const DecoderInfo& info, const RoleSpec& rs,
                                    const std::map<std::string, std::string>& map,
                                    const std::vector<LineRef>& bound_refs) {
        const auto& sigs = reader->signals();
        std::optional<LineRef> ref;
        if (auto it = map.find(rs.name); it != map.end()) {
            ref = findSignal(sigs, it->second, false);
            if (!ref) ref = findSignal(sigs, it->second, true);
            if (ref && ref->bit < 0 && sigs[ref->signal].width > 1)
                throw InputError(fmt::format(
                    "{}: decoder {}: --map {}={}: {} is a vector of {} bits: map one of them "
                    "(--map {}={}[BIT])",
                    facts->file, info.id, rs.name, it->second, signalText(sigs[ref->signal]),
                    sigs[ref->signal].width, rs.name, it->second));
            if (ref) return ref;
            // "--map cs=CS,sclk=CLK" reads as one role bound to a signal "CS,sclk=CLK".
            const bool several = it->second.find(',') != std::string::npos &&
                                 it->second.find('=') != std::string::npos;
            throw InputError(fmt::format(
                "{}: decoder {}: --map {}={}: no such signal in the capture (signals: {}){}",
                facts->file, info.id, rs.name, it->second, signalList(*reader, it->second),
                several ? "; one --map per role: --map ROLE=SIGNAL --map ROLE=SIGNAL" : ""));
        }
        std::vector<std::string> names = {rs.name};
        names.insert(names.end(), rs.aliases.begin(), rs.aliases.end());
        for (const auto& n2 : names) {
            if ((ref = findSignal(sigs, n2, true))) break;
        }
        // Never bind one signal to two roles automatically.
        if (ref)
            for (const auto& b : bound_refs)
                if (b.signal == ref->signal && b.bit == ref->bit) ref.reset();
        return ref;
    }

    void checkOneOfBound(const DecoderInfo& info, const std::vector<int>& role_line) {
        if (info.need_one_of.empty()) return;
        bool any = false;
        for (std::size_t r = 0; r < info.roles.size(); ++r)
            for (const auto& name : info.need_one_of)
                any |= info.roles[r].name == name && role_line[r] >= 0;
        if (!any)
            throw InputError(
                fmt::format("{}: decoder {}: bind at least one of the roles {} (signals: {})",
                            facts->file, info.id, fmt::join(info.need_one_of, ", "),
                            signalList(*reader, info.need_one_of.front())));
    }

    // The selected line of `ref`, selected now if no decoder has it yet.
    int lineOf(const LineRef& ref) {
        for (int i = 0; i < int(lines.size()); ++i)
            if (lines[i].signal == ref.signal && lines[i].bit == ref.bit) return i;
        if (lines.size() == kMaxSelectedLines)  // what an Edge can name
            throw InputError(
                fmt::format("{}: more than {} signals mapped", facts->file, kMaxSelectedLines));
        lines.push_back(ref);
        return int(lines.size()) - 1;
    }

    // Where each selected line's edges go, and whether whole blocks can go to one decoder.
    void routeLines() {
        for (const auto& slot : slots)
            keep_window |= slot.decoder->correlates();
        targets.resize(lines.size());
        for (int s = 0; s < int(slots.size()); ++s)
            for (int r = 0; r < int(slots[s].role_line.size()); ++r)
                if (slots[s].role_line[r] >= 0)
                    targets[slots[s].role_line[r]].push_back(
                        {s, r, slots[s].decoder.get(),
                         slots[s].glitch ? &*slots[s].glitch : nullptr});
        block_path = slots.size() == 1 && !slots[0].glitch;
        for (const auto& tgs : targets) {
            block_path &= tgs.size() == 1;
            role_of_line.push_back(tgs.empty() ? -1 : tgs[0].role);
        }
    }

    void advanceAll(Tick t) {
        for (int i = 0; i < int(slots.size()); ++i) {
            Slot& s = slots[i];
            emitting = i;
            if (s.glitch) s.glitch->release(t, filtered(*s.decoder));
            // Edges the filter still holds lie before t: the decoder may only be told
            // that time has passed up to the oldest of them.
            Tick upto = t;
            if (s.glitch && s.glitch->oldest() != kNoTick) upto = std::min(t, s.glitch->oldest());
            s.decoder->advance(upto);
        }
    }
};

Session::Session(std::vector<DecoderRequest> requests, CaptureReader& reader, std::string file_name)
    : impl_(std::make_unique<Impl>()) {
    impl_->reader = &reader;
    impl_->sinks = &sinks_;
    impl_->facts = &facts_;
    facts_.file = std::move(file_name);
    facts_.format = reader.formatName();
    facts_.capture_start = reader.wallClockStart();
    facts_.timebase = reader.timebase();
    if (requests.empty())
        throw InputError("no decoder chosen: use --proto NAME (see decode --list)");
    std::map<std::string, int> proto_count;
    for (const auto& r : requests)
        proto_count[r.proto]++;
    std::map<std::string, int> proto_seen;
    for (auto& req : requests) {
        const int n = ++proto_seen[req.proto];
        Impl::Slot slot = impl_->makeSlot(
            req, proto_count[req.proto] > 1 ? fmt::format("{}#{}", req.proto, n) : req.proto);
        impl_->bindRoles(slot, req.map);
        facts_.protos.push_back(slot.instance);
        facts_.options[slot.instance] = slot.options.all();
        impl_->slots.push_back(std::move(slot));
    }
    impl_->routeLines();
    reader.select(impl_->lines);
}

Session::~Session() = default;

void Session::setPieceSpeculation(bool on) {
    impl_->speculate = on;
}

Session::PieceStats Session::pieceStats() const {
    return impl_->piece_stats;
}

void Session::requestStop() {
    impl_->stop = true;
}
void Session::setStopFlag(const std::atomic<bool>* flag) {
    impl_->external_stop = flag;
}
void Session::abandonWhenStopped() {
    impl_->abandon_when_stopped = true;
}

namespace {

// A capture whose times in ns would not fit (readers that know the line say it first).
std::string timeTooLate(const std::string& file, Tick t, Tick last) {
    return fmt::format("{}: time {} ticks beyond {}, past what times in ns can hold", file, t,
                       last);
}

}  // namespace

void Session::start() {
    if (started_) return;
    started_ = true;
    Impl& im = *impl_;
    im.levels = im.reader->initialLevels();
    facts_.start = im.reader->startTick();
    im.now = facts_.start;
    startDecoders();
}

void Session::run() {
    start();
    Impl& im = *impl_;
    CaptureReader& reader = *im.reader;
    for (auto* s : sinks_)
        s->begin(facts_);
    // Pieces decoded ahead on the reader's threads, where that applies.
    if (im.speculate && im.block_path && !im.keep_window) {
        Impl::Slot& slot = im.slots[0];
        im.parallel = ParallelVcdPipeline::start(
            reader, {*slot.factory, slot.options, slot.ctx, slot.hints, slot.instance},
            im.role_of_line, slot.decoder, im, im.spare);
    }
    EdgeBlock block;
    block.edges.reserve(kEdgeBlockSize);
    std::uint64_t edges = 0;
    const Tick last_tick = lastTickOf(reader.timebase());
    while (!im.stopped() && reader.next(block)) {
        if (!block.edges.empty() && block.edges.back().t > last_tick)
            throw InputError(timeTooLate(facts_.file, block.edges.back().t, last_tick));
        edges = decodeBlock(block, edges);
        facts_.edges = edges;
        facts_.acquisition = reader.acquisition();
    }
    if (im.parallel) endParallelPath();
    if (im.stopped() && im.abandon_when_stopped) {
        const double seconds = double(im.now - facts_.start) * reader.timebase().secondsPerTick();
        throw Interrupted(interruptedAt(facts_.file,
                                        fmt::format("{:.6g} s into the capture", seconds),
                                        reader.bytesRead(), reader.bytesTotal()));
    }
    // Drain the reader's end (a stopped follow has no end tick yet).
    facts_.end = im.stopped() ? im.now : std::max(reader.endTick(), im.now);
    if (facts_.end > last_tick) throw InputError(timeTooLate(facts_.file, facts_.end, last_tick));
    finishDecoders();
    facts_.bytes = reader.bytesRead();
    facts_.acquisition = reader.acquisition();
    for (auto* s : sinks_)
        s->end(facts_);
}

void Session::startDecoders() {
    Impl& im = *impl_;
    // Fields are built only if a sink reads them or a decoder correlates (it looks at
    // the other decoders' events in the window).
    bool fields_wanted = im.keep_window;
    bool summaries_wanted = false;  // decoders read each other's fields, never summaries
    for (const auto* sink : sinks_) {
        fields_wanted |= sink->readsFields();
        summaries_wanted |= sink->readsSummaries();
    }
    for (int s = 0; s < int(im.slots.size()); ++s) {
        auto& slot = im.slots[s];
        slot.hints.fields_wanted = fields_wanted;
        slot.hints.summaries_wanted = summaries_wanted;
        slot.hints.lines_are_roles = im.block_path && linesAreRoles(im.role_of_line);
        slot.fast = fastPathOf(*slot.decoder);
        if (slot.fast) slot.fast->setHints(slot.hints);
        slot.ctx.timebase = im.reader->timebase();
        slot.ctx.capture_start = facts_.start;
        for (int line : slot.role_line)
            slot.ctx.initial_levels.push_back(line < 0 ? -1 : im.levels[line]);
        slot.ctx.sink = &im;
        im.emitting = s;
        slot.decoder->start(slot.ctx);
        slot.decoder->setSink(&im);
    }
}

std::uint64_t Session::decodeBlock(EdgeBlock& block, std::uint64_t before) {
    Impl& im = *impl_;
    // Repeated values (not edges) dropped in place, unless the reader did.
    Edge* kept = block.edges.data();
    std::size_t n = block.edges.size();
    if (!im.reader->changesOnly()) {
        n = 0;
        for (const Edge& e : block.edges) {
            if (im.levels[e.line] == e.level) continue;
            im.levels[e.line] = e.level;
            kept[n++] = e;
        }
    }
    // A sink drawing the waveform (the HTML report) sees the edges before their events.
    for (auto* s : sinks_)
        if (s->wantsEdges()) {
            if (!block.volts.empty()) s->onVolts(block.volts, block.thresholds);
            s->onEdges(kept, kept + n);
        }
    bool advance = true;
    if (im.parallel) {
        im.emitting = 0;
        advance = im.parallel->decode(kept, kept + n, before);
    } else if (im.block_path) {  // the whole block in one call
        im.emitting = 0;
        feedEdges(*im.slots[0].decoder, im.slots[0].fast, kept, kept + n, im.role_of_line.data());
    } else {
        for (std::size_t i = 0; i < n; ++i)
            for (const auto& tg : im.targets[kept[i].line])
                im.deliver(tg, kept[i].t, kept[i].level);
    }
    if (!block.findings.empty() || block.findings_from != im.findings_from) im.takeFindings(block);
    if (!block.edges.empty()) im.now = std::max(im.now, block.edges.back().t);
    if (block.known_until != kNoTick && block.known_until > im.now) im.now = block.known_until;
    if (advance) im.advanceAll(im.now);
    im.release(false);
    return before + n;
}

void Session::endParallelPath() {
    Impl& im = *impl_;
    const auto& st = im.parallel->stats();
    im.piece_stats = {st.pieces, st.spliced, st.edges_ahead};
    // The targets name the decoder that took over.
    for (auto& tgs : im.targets)
        for (auto& tg : tgs)
            tg.decoder = im.slots[std::size_t(tg.slot)].decoder.get();
    // Stopped within a piece decoded ahead: the decoder has seen it to its end.
    if (im.stopped()) im.now = std::max(im.now, im.parallel->decodedUntil());
}

void Session::finishDecoders() {
    Impl& im = *impl_;
    for (int s = 0; s < int(im.slots.size()); ++s) {
        auto& slot = im.slots[s];
        im.emitting = s;
        if (slot.glitch) slot.glitch->flush(Impl::filtered(*slot.decoder));
        slot.decoder->advance(facts_.end);
        slot.decoder->finish(facts_.end);
    }
    im.cut_from = facts_.end;
    im.release(true);
    facts_.advice.clear();
    for (const auto& slot : im.slots)
        for (const auto& a : slot.decoder->advice())
            facts_.advice.push_back(slot.instance + ": " + a);
    for (const auto& note : im.reader->notes())
        facts_.advice.push_back(note);
    if (im.cut_at_end && im.reader->endsAtLastChange())
        facts_.advice.push_back(fmt::format(
            "the last frame is cut by the capture's end (short_frame), but a {} records no end: "
            "it ends at its last change, and the traffic may have gone on past it",
            im.reader->formatName()));
    facts_.advice.insert(facts_.advice.end(), notes_.begin(), notes_.end());
}

namespace {
struct CollectSink : OutputSink {
    std::vector<Event>* out;
    void onEvent(const Event& e, const CaptureFacts&) override { out->push_back(e); }
};
}  // namespace

std::vector<Event> decodeWaveform(const Waveform& w, const std::vector<DecoderRequest>& requests) {
    auto reader = memoryReader(w);
    Session s(requests, *reader, "memory");
    std::vector<Event> events;
    CollectSink sink;
    sink.out = &events;
    s.addSink(&sink);
    s.run();
    return events;
}

}  // namespace busdecode
