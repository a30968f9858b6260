#include "analog_capture.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include <fmt/format.h>

#include "analog_lines.h"
#include "capture_events.h"
#include "core/options.h"
#include "differential_pairs.h"
#include "signal_quality.h"

namespace busdecode {

namespace {

// Rows held back at the start to find each line's levels and the sample period.
constexpr std::size_t kPrefixRows = 1 << 18;

std::string volts(double v) {
    return fmt::format("{:.4g} V", v);
}

class AnalogReader : public CaptureReader {
public:
    AnalogReader(std::unique_ptr<SampleSource> src, const OpenOptions& opts)
        : src_(std::move(src)), opts_(opts) {
        channels_ = src_->channels();
        for (const auto& c : channels_)
            signals_.push_back({c.name, c.full_name, 1});
        addPairs();
        checkThresholdNames();
        row_.resize(src_->slots() + pairs_.size());
        readPrefix();
        chooseTimebase();
    }

    const std::vector<SignalInfo>& signals() const override { return signals_; }
    Timebase timebase() const override { return tb_; }
    std::string formatName() const override { return src_->formatName(); }
    std::string wallClockStart() const override { return src_->wallClockStart(); }

    void select(const std::vector<LineRef>& lines) override {
        checkSelection(lines);
        lines_.clear();
        for (const auto& ref : lines) {
            if (ref.signal < 0 || ref.signal >= int(signals_.size()))
                throw std::out_of_range("AnalogReader::select");
            const AnalogChannel& c = channels_[std::size_t(ref.signal)];
            Line l;
            l.channel = std::size_t(ref.signal);
            l.slot = c.slot;
            l.bit = c.bit;
            if (l.slot >= src_->slots()) {
                l.pair = pairs_[l.slot - src_->slots()];
                l.watch = std::make_unique<PairWatch>(graceTicks());
            }
            lines_.push_back(std::move(l));
        }
    }

    std::vector<std::uint8_t> initialLevels() override {
        if (!started_) start();
        std::vector<std::uint8_t> out;
        for (const auto& l : lines_)
            out.push_back(l.level);
        return out;
    }
    Tick startTick() const override { return start_tick_; }
    Tick endTick() const override { return end_tick_; }
    std::uint64_t bytesRead() const override { return src_->bytesRead(); }
    std::uint64_t bytesTotal() const override { return src_->bytesTotal(); }
    bool changesOnly() const override { return true; }

    bool next(EdgeBlock& block) override {
        block.clear();
        if (!started_) start();
        if (done_) return false;
        while (block.edges.size() + order_.held() + lines_.size() < kEdgeBlockSize &&
               block.volts.size() < kVoltBlock) {
            double t;
            if (!nextSample(t)) {
                if (src_->waiting()) break;  // followed, no new row yet: hand on what is decoded
                done_ = true;
                finishLearning();
                order_.release(kMaxEdgeTick, block.edges);
                block.known_until = end_tick_;
                addFindings(block);
                handVolts(block);
                return !block.edges.empty() || !block.volts.empty() || !block.findings.empty();
            }
            takeSample(t, block.edges);
            if (opts_.keep_voltages) keepVolts(block.volts);
        }
        block.known_until = bound_;
        addFindings(block);
        handVolts(block);
        return true;
    }

    std::vector<std::string> notes() const override;
    bool readsVoltages() const override { return true; }

private:
    // Pair faults closed so far; at the end, the faults still open and each line's
    // `signal` event too.
    void addFindings(EdgeBlock& block) {
        for (auto& l : lines_) {
            if (!l.watch) continue;
            if (done_) l.watch->finish(end_tick_);
            addPairFindings(signals_[l.channel].name, *l.watch, block);
        }
        for (auto& f : gap_findings_)
            block.findings.push_back(std::move(f));
        gap_findings_.clear();
        if (!done_) return;
        for (const auto& l : lines_) {
            if (l.bit >= 0) continue;
            Event e = l.quality.event(signals_[l.channel].name, l.settings.threshold,
                                      l.settings.hysteresis, l.trigger.reversals());
            // At the end: a summary of the whole line, after every event it sums up.
            e.start = e.end = end_tick_;
            block.findings.push_back(std::move(e));
        }
    }

    // A differential pair: its line is the difference of two channels' voltages.
    struct Pair {
        std::size_t slot[2] = {0, 0};
    };
    struct Line {
        std::size_t channel = 0, slot = 0;
        int bit = -1;
        // A pair's wires, each with a trigger of its own, for its PairWatch.
        Pair pair;
        std::unique_ptr<PairWatch> watch;
        SchmittLine wire[2];
        std::pair<double, double> wire_levels[2];
        SignalQuality quality;
        SchmittLine trigger;
        SchmittSettings settings;
        // A prefix of one level: edges wait for the levels the later samples show.
        FlatLineLearner learner;
        bool learning = false, learned = false;
        std::pair<double, double> levels;
        std::uint8_t level = 0;
        Tick last = kMinEdgeTick;
        std::uint64_t edges = 0;
    };

    // OpenOptions::pairs whose two wires are analog channels of this capture.
    void addPairs() {
        for (const auto& text : opts_.pairs) {
            std::string p, n;
            if (!splitPair(text, p, n) || findSignal(signals_, text) >= 0) continue;
            const int wp = findSignal(signals_, p), wn = findSignal(signals_, n);
            if (wp < 0 || wn < 0 || channels_[std::size_t(wp)].bit >= 0 ||
                channels_[std::size_t(wn)].bit >= 0)
                continue;
            pairs_.push_back({{channels_[std::size_t(wp)].slot, channels_[std::size_t(wn)].slot}});
            channels_.push_back({text, text, src_->slots() + pairs_.size() - 1, -1});
            signals_.push_back({text, text, 1});
        }
    }
    void computePairs() {
        const std::size_t base = src_->slots();
        for (std::size_t k = 0; k < pairs_.size(); ++k)
            row_[base + k] = row_[pairs_[k].slot[0]] - row_[pairs_[k].slot[1]];
    }
    float prefixValue(std::size_t row, std::size_t slot) const {
        const std::size_t n = src_->slots();
        if (slot < n) return prefix_v_[row * n + slot];
        const Pair& p = pairs_[slot - n];
        return prefix_v_[row * n + p.slot[0]] - prefix_v_[row * n + p.slot[1]];
    }
    // Equal wire levels for up to three samples (or 100 ns) are skew, not a fault.
    Tick graceTicks() const {
        return Tick(std::max(3 * period_ * ticks_per_s_, 1e-7 * ticks_per_s_)) + 1;
    }

    void checkThresholdNames() const {
        for (const auto& threshold : opts_.thresholds) {
            const std::string& name = threshold.first;  // not a binding: lambdas capture it
            if (!name.empty() && std::none_of(signals_.begin(), signals_.end(), [&](auto& s) {
                    return s.name == name || s.full_name == name;
                }))
                throw InputError(fmt::format("--threshold {}={}: {} has no signal '{}'", name,
                                             threshold.second, src_->fileName(), name));
        }
    }

    bool nextRow(double& t) {
        if (!src_->next(t, row_.data())) return false;
        holdNoData();
        computePairs();
        // A value beyond float's range (or a pair's difference) would poison the levels.
        for (const float v : row_)
            if (!std::isfinite(v)) src_->fail("a value beyond ±3.4e38 (or a pair's difference)");
        if (have_time_ && t < last_t_)
            src_->fail(fmt::format("time going backwards ({} s after {} s)", t, last_t_));
        have_time_ = true;
        last_t_ = t;
        return true;
    }

    // A sample of 9.9e37 (over range, or no data) is no voltage: each takes the value of
    // the sample before it on its channel, so that it makes no edge and no overshoot;
    // notes() counts them. Those before a channel's first voltage take that voltage
    // (fillLeadingNoData()), or 0 V beyond the prefix.
    void holdNoData() {
        if (held_.empty()) held_.assign(src_->slots(), {});
        for (std::size_t s = 0; s < held_.size(); ++s) {
            Held& h = held_[s];
            if (std::abs(row_[s]) > kNoDataVolts) {
                row_[s] = h.value;
                ++h.count;
            } else {
                h.value = row_[s];
                if (!h.seen) h.leading = h.count;
                h.seen = true;
            }
        }
    }
    void fillLeadingNoData() {
        const std::size_t n = src_->slots();
        for (std::size_t s = 0; s < held_.size(); ++s)
            for (std::size_t r = 0; held_[s].seen && r < held_[s].leading; ++r)
                prefix_v_[r * n + s] = prefix_v_[held_[s].leading * n + s];
    }

    void readPrefix() {
        double t;
        while (prefix_t_.size() < kPrefixRows) {
            if (!nextRow(t)) {
                // A followed file that stops growing: the levels from what it holds, once
                // it holds two rows (a period).
                if (src_->waiting() && prefix_t_.size() < 2) continue;
                break;
            }
            if (const std::uint64_t k = src_->segmentBegun())
                prefix_segments_.push_back({prefix_t_.size(), k});
            prefix_t_.push_back(t);
            prefix_v_.insert(prefix_v_.end(), row_.begin(),
                             row_.begin() + std::ptrdiff_t(src_->slots()));
        }
        fillLeadingNoData();
    }

    void chooseTimebase() {
        double period = src_->period();
        if (!(period > 0) && prefix_t_.size() > 1)
            period = (prefix_t_.back() - prefix_t_.front()) / double(prefix_t_.size() - 1);
        int r = 9;
        while (r < 12 && period > 0 && period / 100 < std::pow(10.0, -r))
            ++r;
        tb_ = Timebase{1, std::int64_t(std::llround(std::pow(10.0, r)))};
        ticks_per_s_ = double(tb_.den);
        period_ = period > 0 ? period : 0;
    }

    void start();
    const std::string& channelOfSlot(std::size_t slot) const {
        for (const auto& c : channels_)
            if (c.slot == slot && c.bit < 0) return c.name;
        return channels_.front().name;
    }
    SchmittSettings settingsFor(const Line& l, SchmittSettings s) const;

    // The prefix first, then the rest; segment_begun_ as SampleSource::segmentBegun().
    bool nextSample(double& t) {
        segment_begun_ = 0;
        if (prefix_at_ < prefix_t_.size()) {
            t = prefix_t_[prefix_at_];
            const std::size_t n = src_->slots();
            std::memcpy(row_.data(), &prefix_v_[prefix_at_ * n], n * sizeof(float));
            computePairs();
            if (!prefix_segments_.empty() && prefix_segments_.front().first == prefix_at_) {
                segment_begun_ = prefix_segments_.front().second;
                prefix_segments_.erase(prefix_segments_.begin());
            }
            if (++prefix_at_ == prefix_t_.size()) {
                prefix_t_ = {};
                prefix_v_ = {};
            }
            return true;
        }
        if (!nextRow(t)) return false;
        segment_begun_ = src_->segmentBegun();
        return true;
    }

    Tick toTick(double t) const {
        const double ticks = std::nearbyint(t);
        if (!(ticks >= double(kMinEdgeTick) && ticks <= double(kMaxEdgeTick)))
            src_->fail("time out of range");
        return Tick(ticks);
    }

    void takeSample(double t_s, std::vector<Edge>& out) {
        const double t = t_s * ticks_per_s_;
        if (segment_begun_) startSegment(t);
        for (auto& l : lines_)
            if (l.bit < 0 && !l.learning) l.quality.feed(t_s, row_[l.slot]);
        end_tick_ = toTick(t);
        double bound = t;
        for (std::size_t i = 0; i < lines_.size(); ++i) {
            Line& l = lines_[i];
            if (l.learning) {
                learn(l, i, t);
                bound =
                    std::min(bound, l.learning ? l.learner.earliest(t) : l.trigger.earliestNext());
                continue;
            }
            double et = t;
            bool edge;
            if (l.bit >= 0) {
                const std::uint8_t level = (unsigned(row_[l.slot]) >> l.bit) & 1u;
                edge = level != l.level;
                l.level = level;
            } else {
                edge = l.trigger.feed(t, row_[l.slot], et);
                l.level = l.trigger.level();
                bound = std::min(bound, l.trigger.earliestNext());
                if (l.watch) watchWires(l, t);
            }
            if (edge) pushEdge(l, i, et);
        }
        bound_ = std::max(Tick(std::floor(bound)), start_tick_);
        order_.release(bound_, out);
    }

    // The first sample of a sequence capture's next segment, after dead time that was not
    // recorded: a gap finding, and each analog line starts afresh here, a level that
    // changed in the gap an edge at this sample, with no crossing fitted through the gap.
    void startSegment(double t) {
        gap_findings_.push_back(segmentGapEvent(end_tick_, toTick(t), segment_begun_));
        for (std::size_t i = 0; i < lines_.size(); ++i) {
            Line& l = lines_[i];
            if (l.bit >= 0 || l.learning) continue;
            double et;
            if (l.trigger.flushPending(et)) pushEdge(l, i, et);
            l.quality.restart();
            const std::uint8_t level = l.trigger.start(t, row_[l.slot]);
            if (level != l.level) {
                l.level = level;
                pushEdge(l, i, t);
            }
            for (int w = 0; l.watch && w < 2; ++w) {
                if (l.wire[w].flushPending(et)) l.watch->edge(toTick(et), w, l.wire[w].level());
                const std::uint8_t wl = l.wire[w].level();
                if (l.wire[w].start(t, row_[l.pair.slot[w]]) != wl)
                    l.watch->edge(toTick(t), w, l.wire[w].level());
            }
        }
    }

    void pushEdge(Line& l, std::size_t i, double t) {
        l.last = std::max({l.last, start_tick_, toTick(t)});
        ++l.edges;
        order_.push(l.last, std::uint32_t(i), l.level);
    }

    // Held edges of other lines wait for a learning line; this many end its wait early.
    static constexpr std::size_t kMaxHeldEdges = kEdgeBlockSize / 4;
    void learn(Line& l, std::size_t i, double t) {
        const double v = row_[l.slot];
        l.trigger.see(v);
        if (l.learner.add(t, v) || (l.learner.departed() && order_.held() >= kMaxHeldEdges))
            resolve(l, i);
    }
    void resolve(Line& l, std::size_t i);
    void finishLearning() {
        for (std::size_t i = 0; i < lines_.size(); ++i)
            if (lines_[i].learning) resolve(lines_[i], i);
    }

    // A block ends after this many voltage samples, so that a quiet stretch stays bounded.
    static constexpr std::size_t kVoltBlock = 16384;
    void keepVolts(std::vector<VoltSample>& out) const {
        for (std::size_t i = 0; i < lines_.size(); ++i)
            if (lines_[i].bit < 0)
                out.push_back({end_tick_, row_[lines_[i].slot], std::uint32_t(i)});
    }
    void handVolts(EdgeBlock& block) const {
        if (block.volts.empty()) return;
        for (std::size_t i = 0; i < lines_.size(); ++i)
            if (lines_[i].bit < 0)
                block.thresholds.push_back({std::uint32_t(i), float(lines_[i].settings.threshold),
                                            float(lines_[i].settings.hysteresis)});
    }

    void watchWires(Line& l, double t) {
        for (int w = 0; w < 2; ++w) {
            double et;
            if (l.wire[w].feed(t, row_[l.pair.slot[w]], et) &&
                l.watch->edge(toTick(et), w, l.wire[w].level()))
                checkOpen(l);
        }
    }
    // A wire that stopped following and sits in the middle half of the pair's swing is
    // open (floating), not driven to a level. The pair's: an open wire's own levels may
    // be the one it drove and the one it floats at.
    void checkOpen(Line& l) const {
        const int w = l.watch->stuckWire();
        const double low = std::min(l.wire_levels[0].first, l.wire_levels[1].first);
        const double high = std::max(l.wire_levels[0].second, l.wire_levels[1].second);
        const double v = row_[l.pair.slot[w]], quarter = (high - low) / 4;
        if (quarter > 0 && v > low + quarter && v < high - quarter) l.watch->markOpen();
    }

    std::unique_ptr<SampleSource> src_;
    std::vector<AnalogChannel> channels_;
    std::vector<Pair> pairs_;
    double period_ = 0;
    OpenOptions opts_;
    std::vector<SignalInfo> signals_;
    std::vector<float> row_;
    std::vector<double> prefix_t_;
    std::vector<float> prefix_v_;
    std::size_t prefix_at_ = 0;
    std::vector<std::pair<std::size_t, std::uint64_t>> prefix_segments_;  // (row, segment)
    std::uint64_t segment_begun_ = 0;
    std::vector<Event> gap_findings_;  // segment gaps not yet handed out
    struct Held {
        float value = 0;
        std::uint64_t count = 0;    // samples of 9.9e37 replaced
        std::uint64_t leading = 0;  // of them, before the first voltage
        bool seen = false;          // a voltage so far
    };
    std::vector<Held> held_;  // per slot: holdNoData()
    std::vector<Line> lines_;
    EdgeOrderer order_;
    Timebase tb_;
    double ticks_per_s_ = 1e9;
    double last_t_ = 0;
    bool have_time_ = false, started_ = false, done_ = false;
    Tick start_tick_ = 0, end_tick_ = 0, bound_ = 0;
};

// The settings the line's data gave, overridden by --threshold and --hysteresis.
SchmittSettings AnalogReader::settingsFor(const Line& l, SchmittSettings s) const {
    const SignalInfo& sig = signals_[l.channel];
    bool given = false;
    for (const auto& [name, v] : opts_.thresholds)
        if (name.empty() || name == sig.name || name == sig.full_name) {
            s.threshold = v;
            given = true;
        }
    if (given) {
        s.from_data = false;
        if (s.flat) s.hysteresis = 0;
        s.flat = false;
    }
    if (opts_.hysteresis >= 0) s.hysteresis = opts_.hysteresis;
    return s;
}

// The held samples of a line whose prefix was flat: its levels, then its edges in them.
// Still one level (a spike): wait for the next departure; at the end, no edges.
void AnalogReader::resolve(Line& l, std::size_t i) {
    const auto& held = l.learner.held();
    LevelEstimator est;
    for (const auto& [t, v] : held)
        est.add(v);
    const LevelEstimate found = est.estimate();
    SchmittSettings s = found.settings;
    if (s.flat && !done_) return l.learner.restart();
    l.learning = false;
    if (s.flat || !l.learner.departed()) return l.learner.clear();
    if (opts_.hysteresis >= 0) s.hysteresis = opts_.hysteresis;
    l.settings = s;
    l.levels = found.levels;
    l.learned = true;
    l.trigger.configure(s);
    l.quality.configure(l.levels.first, l.levels.second);
    // The level before the held samples was a guess: a wrong one is put right at once.
    const std::uint8_t level = l.trigger.start(held[0].first, held[0].second);
    if (level != l.level) {
        l.level = level;
        pushEdge(l, i, held[0].first);
    }
    for (std::size_t k = 1; k < held.size(); ++k) {
        double et;
        l.quality.feed(held[k].first / ticks_per_s_, held[k].second);
        if (!l.trigger.feed(held[k].first, held[k].second, et)) continue;
        l.level = l.trigger.level();
        pushEdge(l, i, et);
    }
    l.learner.clear();
}

void AnalogReader::start() {
    started_ = true;
    for (auto& l : lines_) {
        if (l.bit >= 0) continue;
        LevelEstimator est;
        for (std::size_t r = 0; r < prefix_t_.size(); ++r)
            est.add(prefixValue(r, l.slot));
        const LevelEstimate found = est.estimate();
        l.settings = settingsFor(l, found.settings);
        l.levels = found.levels;
        l.learning = l.settings.flat && !l.watch;
        if (l.learning) l.learner.configure(found.settings);
        l.trigger.configure(l.settings);
        l.quality.configure(l.levels.first, l.levels.second);
        for (int w = 0; l.watch && w < 2; ++w) {
            LevelEstimator wire;
            for (std::size_t r = 0; r < prefix_t_.size(); ++r)
                wire.add(prefixValue(r, l.pair.slot[w]));
            const LevelEstimate found = wire.estimate();
            l.wire[w].configure(found.settings);
            l.wire_levels[w] = found.levels;
        }
    }
    double t;
    if (!nextSample(t)) {
        done_ = true;
        return;
    }
    const double ticks = t * ticks_per_s_;
    start_tick_ = end_tick_ = bound_ = toTick(ticks);
    for (std::size_t i = 0; i < lines_.size(); ++i) {
        Line& l = lines_[i];
        l.level = l.bit >= 0 ? (unsigned(row_[l.slot]) >> l.bit) & 1u
                             : l.trigger.start(ticks, row_[l.slot]);
        // A line idle clear above 0 V is guessed high until its levels show.
        if (l.learning) {
            l.level = l.learner.idleAboveZero();
            learn(l, i, ticks);
        }
        if (l.watch)
            l.watch->start(start_tick_, l.wire[0].start(ticks, row_[l.pair.slot[0]]),
                           l.wire[1].start(ticks, row_[l.pair.slot[1]]));
    }
}

std::vector<std::string> AnalogReader::notes() const {
    std::vector<std::string> out;
    for (const auto& l : lines_) {
        if (l.bit >= 0) continue;
        const std::string& name = signals_[l.channel].name;
        if (!(l.trigger.minSeen() <= l.trigger.maxSeen())) {  // not one sample: no levels
            out.push_back(fmt::format("{}: the capture holds no samples", name));
            continue;
        }
        const SchmittSettings& s = l.settings;
        std::string how = s.flat        ? "one level only in its first samples: a guess"
                          : s.from_data ? fmt::format("from the data{}: levels {} and {}",
                                                      l.learned ? " after its idle start" : "",
                                                      volts(l.levels.first), volts(l.levels.second))
                                        : "as given";
        out.push_back(fmt::format("{}: threshold {}, hysteresis {} ({})", name, volts(s.threshold),
                                  volts(s.hysteresis), how));
        if (l.edges == 0)
            out.push_back(fmt::format(
                "{} never crossed its threshold {} (its range {} to {}): give --threshold {}=VOLTS",
                name, volts(s.threshold), volts(l.trigger.minSeen()), volts(l.trigger.maxSeen()),
                name));
        if (l.watch)
            for (auto& n : pairFaultNotes(name, *l.watch, tb_))
                out.push_back(std::move(n));
        const bool pair = l.slot >= src_->slots();
        for (const std::size_t slot :
             pair ? std::vector{l.pair.slot[0], l.pair.slot[1]} : std::vector{l.slot})
            if (slot < held_.size() && held_[slot].count)
                out.push_back(fmt::format(
                    "{}: {} samples of 9.9e37 (over range, or no data) each taken as the "
                    "sample before",
                    channelOfSlot(slot), held_[slot].count));
    }
    return out;
}

}  // namespace

std::unique_ptr<CaptureReader> analogReader(std::unique_ptr<SampleSource> src,
                                            const OpenOptions& opts) {
    return std::make_unique<AnalogReader>(std::move(src), opts);
}

}  // namespace busdecode
