#include "differential_pairs.h"

#include <algorithm>
#include <charconv>

#include <fmt/format.h>

#include "core/options.h"

namespace busdecode {

void PairWatch::start(Tick t, std::uint8_t p, std::uint8_t n) {
    level_[0] = p;
    level_[1] = n;
    equal_since_ = p == n ? t : kNoTick;
}

const char* pairFaultKindName(PairFaultKind k) {
    switch (k) {
        case PairFaultKind::Open:
            return "open";
        case PairFaultKind::Shorted:
            return "shorted";
        case PairFaultKind::Stuck:
            break;
    }
    return "stuck";
}

bool PairWatch::openFault() {
    if (in_fault_) return false;
    in_fault_ = true;
    open_ = false;
    fault_start_ = equal_since_;
    fault_edges_[0] = fault_edges_[1] = 0;
    return true;
}

bool PairWatch::edge(Tick t, int wire, std::uint8_t level) {
    if (level == level_[wire]) return false;
    bool opened = false;
    // An equal stretch longer than the skew between the wires ends here: a fault.
    if (equal_since_ != kNoTick && t - equal_since_ > grace_) {
        opened = openFault();
        last_bad_ = t;
        clean_edges_[0] = clean_edges_[1] = 0;
    }
    level_[wire] = level;
    if (in_fault_) {
        ++fault_edges_[wire];
        ++clean_edges_[wire];
        // Both wires following each other again, edge for edge: the fault is over.
        if (clean_edges_[0] >= 2 && clean_edges_[1] >= 2) closeFault(last_bad_);
    }
    if (level_[0] == level_[1]) {
        if (equal_since_ == kNoTick) equal_since_ = t;
    } else {
        equal_since_ = kNoTick;
    }
    return opened;
}

void PairWatch::finish(Tick t) {
    if (equal_since_ != kNoTick && t - equal_since_ > grace_) openFault();
    // Not seen following each other again: the fault lasts to the end.
    if (in_fault_) closeFault(t);
    equal_since_ = kNoTick;
}

void PairWatch::closeFault(Tick end) {
    ++count_;
    // Both wires moving while equal: tied together; one still: stuck (or open).
    const std::uint64_t lo = std::min(fault_edges_[0], fault_edges_[1]);
    const std::uint64_t hi = std::max(fault_edges_[0], fault_edges_[1]);
    const PairFaultKind kind = lo >= 2 && 2 * lo >= hi ? PairFaultKind::Shorted
                               : open_                 ? PairFaultKind::Open
                                                       : PairFaultKind::Stuck;
    const PairFault f{fault_start_, end, stuck(), kind};
    if (faults_.size() < kKeptFaults) faults_.push_back(f);
    closed_.push_back(f);
    in_fault_ = false;
}

bool splitPair(const std::string& text, std::string& positive, std::string& negative) {
    const auto comma = text.find(',');
    if (comma == std::string::npos || text.find(',', comma + 1) != std::string::npos) return false;
    positive = text.substr(0, comma);
    negative = text.substr(comma + 1);
    // "sclk=A,cs=B" is two roles written as one, not a pair (the session words that).
    return !positive.empty() && !negative.empty() && text.find('=') == std::string::npos;
}

int findSignal(const std::vector<SignalInfo>& signals, const std::string& text) {
    for (std::size_t i = 0; i < signals.size(); ++i)
        if (signals[i].name == text || signals[i].full_name == text) return int(i);
    int index = -1;
    const auto [p, ec] = std::from_chars(text.data(), text.data() + text.size(), index);
    if (ec == std::errc() && p == text.data() + text.size() && index >= 0 &&
        index < int(signals.size()))
        return index;
    return -1;
}

std::vector<std::string> pairFaultNotes(const std::string& pair, const PairWatch& watch,
                                        const Timebase& tb) {
    std::vector<std::string> out;
    std::string p, n;
    splitPair(pair, p, n);
    for (const auto& f : watch.faults())
        out.push_back(
            fmt::format("{}: pair_fault from {:.9f} s to {:.9f} s: {} does not follow {} ({})",
                        pair, double(tb.toNs(f.start)) / 1e9, double(tb.toNs(f.end)) / 1e9,
                        f.wire ? n : p, f.wire ? p : n, pairFaultKindName(f.kind)));
    if (watch.faultCount() > watch.faults().size())
        out.push_back(fmt::format("{}: {} more pair faults", pair,
                                  watch.faultCount() - watch.faults().size()));
    return out;
}

Event pairFaultEvent(const std::string& pair, const PairFault& f) {
    std::string p, n;
    splitPair(pair, p, n);
    const std::string& wire = f.wire ? n : p;
    const std::string& working = f.wire ? p : n;
    Event e;
    e.proto = "capture";
    e.type = "pair_fault";
    e.start = f.start;
    e.end = f.end;
    e.add("pair", pair).add("wire", wire).add("working", working);
    e.add("kind", std::string(pairFaultKindName(f.kind)));
    e.error("pair_fault");
    e.summary = fmt::format("{}: {} does not follow {} ({})", pair, wire, working,
                            pairFaultKindName(f.kind));
    return e;
}

void addPairFindings(const std::string& pair, PairWatch& watch, EdgeBlock& block) {
    std::vector<PairFault> closed;
    watch.takeClosed(closed);
    for (const auto& f : closed)
        block.findings.push_back(pairFaultEvent(pair, f));
    const Tick from = watch.pendingFrom();
    if (from != kNoTick && (block.findings_from == kNoTick || from < block.findings_from))
        block.findings_from = from;
}

namespace {

// Logic lines in pairs: the positive wire decodes, or the negative one inverted while
// the positive one is at fault.
class PairedReader : public CaptureReader {
public:
    PairedReader(std::unique_ptr<CaptureReader> inner, const std::vector<std::string>& pairs)
        : in_(std::move(inner)), signals_(in_->signals()) {
        for (const auto& text : pairs) {
            std::string p, n;
            if (findSignal(signals_, text) >= 0 || !splitPair(text, p, n)) continue;
            const int wp = findSignal(in_->signals(), p), wn = findSignal(in_->signals(), n);
            if (wp < 0 || wn < 0) continue;  // the session names the signal it cannot bind
            pairs_.push_back({text, wp, wn});
            signals_.push_back({text, text, 1});
        }
    }

    const std::vector<SignalInfo>& signals() const override { return signals_; }
    Timebase timebase() const override { return in_->timebase(); }
    std::string formatName() const override { return in_->formatName(); }
    std::string wallClockStart() const override { return in_->wallClockStart(); }
    Tick startTick() const override { return in_->startTick(); }
    Tick endTick() const override { return in_->endTick(); }
    std::uint64_t bytesRead() const override { return in_->bytesRead(); }
    std::uint64_t bytesTotal() const override { return in_->bytesTotal(); }

    void select(const std::vector<LineRef>& lines) override;
    std::vector<std::uint8_t> initialLevels() override;
    bool next(EdgeBlock& block) override;
    std::vector<std::string> notes() const override;
    bool readsVoltages() const override { return in_->readsVoltages(); }
    bool endsAtLastChange() const override { return in_->endsAtLastChange(); }

private:
    struct Pair {
        std::string name;
        int wire[2];
    };
    struct Selected {
        int pair = -1;                    // index into pairs_, or -1: a plain line
        std::uint32_t inner[2] = {0, 0};  // its lines in the inner selection
        std::uint8_t level = 0;
        std::unique_ptr<PairWatch> watch;
    };
    std::uint32_t innerLine(const LineRef& ref) {
        for (std::size_t i = 0; i < inner_sel_.size(); ++i)
            if (inner_sel_[i].signal == ref.signal && inner_sel_[i].bit == ref.bit)
                return std::uint32_t(i);
        inner_sel_.push_back(ref);
        return std::uint32_t(inner_sel_.size() - 1);
    }
    std::uint8_t pairLevel(const Selected& s) const {
        return s.watch->working() == 0 ? wire_level_[s.inner[0]] : !wire_level_[s.inner[1]];
    }

    std::unique_ptr<CaptureReader> in_;
    std::vector<SignalInfo> signals_;
    std::vector<Pair> pairs_;
    std::vector<LineRef> inner_sel_;
    std::vector<Selected> sel_;
    // Per inner line: the selected lines it feeds (as wire 0 or 1 of a pair, or plain).
    std::vector<std::vector<std::pair<std::uint32_t, int>>> feeds_;
    std::vector<std::uint8_t> wire_level_;
    EdgeBlock in_block_;
    bool ended_ = false;
};

void PairedReader::select(const std::vector<LineRef>& lines) {
    checkSelection(lines);
    const int plain = int(in_->signals().size());
    sel_.clear();
    for (const auto& ref : lines) {
        Selected s;
        if (ref.signal >= plain) {
            s.pair = ref.signal - plain;
            for (int w = 0; w < 2; ++w)
                s.inner[w] = innerLine({pairs_[std::size_t(s.pair)].wire[w], -1});
            s.watch = std::make_unique<PairWatch>(Tick(in_->timebase().fromNs(100)) + 2);
        } else {
            s.inner[0] = innerLine(ref);
        }
        sel_.push_back(std::move(s));
    }
    if (inner_sel_.size() > kMaxSelectedLines)
        throw InputError("differential pairs: more than 128 wires to read");
    in_->select(inner_sel_);
    feeds_.assign(inner_sel_.size(), {});
    for (std::size_t i = 0; i < sel_.size(); ++i) {
        feeds_[sel_[i].inner[0]].push_back({std::uint32_t(i), 0});
        if (sel_[i].pair >= 0) feeds_[sel_[i].inner[1]].push_back({std::uint32_t(i), 1});
    }
}

std::vector<std::uint8_t> PairedReader::initialLevels() {
    wire_level_ = in_->initialLevels();
    const Tick t0 = in_->startTick();
    std::vector<std::uint8_t> out;
    for (auto& s : sel_) {
        if (s.watch) s.watch->start(t0, wire_level_[s.inner[0]], wire_level_[s.inner[1]]);
        s.level = s.watch ? pairLevel(s) : wire_level_[s.inner[0]];
        out.push_back(s.level);
    }
    return out;
}

bool PairedReader::next(EdgeBlock& block) {
    block.clear();
    if (wire_level_.empty()) initialLevels();
    if (ended_) return false;
    const bool more = in_->next(in_block_);
    for (const Edge& e : in_block_.edges) {
        wire_level_[e.line] = std::uint8_t(e.level);
        for (const auto& [line, wire] : feeds_[e.line]) {
            Selected& s = sel_[line];
            if (s.watch) s.watch->edge(e.t, wire, std::uint8_t(e.level));
            const std::uint8_t level = s.watch ? pairLevel(s) : std::uint8_t(e.level);
            if (level != s.level) {
                s.level = level;
                block.edges.push_back({e.t, line, level});
            }
        }
    }
    // Analog lines passed through keep their samples (an analog pair is the analog
    // reader's own line, passed through too).
    for (const VoltSample& v : in_block_.volts)
        for (const auto& [line, wire] : feeds_[v.line])
            if (sel_[line].pair < 0) block.volts.push_back({v.t, v.volts, line});
    for (const LineThreshold& th : in_block_.thresholds)
        for (const auto& [line, wire] : feeds_[th.line])
            if (sel_[line].pair < 0)
                block.thresholds.push_back({line, th.threshold, th.hysteresis});
    block.known_until = in_block_.known_until;
    block.findings = std::move(in_block_.findings);
    block.findings_from = in_block_.findings_from;
    ended_ = !more;
    for (auto& s : sel_) {
        if (!s.watch) continue;
        if (ended_) s.watch->finish(in_->endTick());
        addPairFindings(pairs_[std::size_t(s.pair)].name, *s.watch, block);
    }
    return more || !block.edges.empty() || !block.volts.empty() || !block.findings.empty();
}

std::vector<std::string> PairedReader::notes() const {
    std::vector<std::string> out = in_->notes();
    for (const auto& s : sel_)
        if (s.watch)
            for (auto& n :
                 pairFaultNotes(pairs_[std::size_t(s.pair)].name, *s.watch, in_->timebase()))
                out.push_back(std::move(n));
    return out;
}

}  // namespace

std::unique_ptr<CaptureReader> pairedReader(std::unique_ptr<CaptureReader> inner,
                                            const std::vector<std::string>& pairs) {
    return std::make_unique<PairedReader>(std::move(inner), pairs);
}

}  // namespace busdecode
