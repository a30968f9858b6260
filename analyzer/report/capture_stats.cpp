#include "capture_stats.h"

#include <algorithm>
#include <cmath>

#include "sinks/event_format.h"

namespace busdecode {

namespace {

bool endsWith(const std::string& s, const char* suffix) {
    const std::string_view sv(suffix);
    return s.size() >= sv.size() && s.compare(s.size() - sv.size(), sv.size(), sv) == 0;
}

bool isNumber(const Value& v) {
    return std::holds_alternative<std::int64_t>(v) || std::holds_alternative<std::uint64_t>(v) ||
           std::holds_alternative<double>(v);
}

// BiSS status bits are sent active low: 1 = no error / warning.
bool isActiveLowFlag(const std::string& key) {
    return key == "nE" || key == "nW";
}

// A position as received in Gray code (a TMC8100 raw_position reply, whose binary twin
// follows it): counted with the binary ones, it would make steps of thousands of counts.
bool isGrayWord(const Event& e) {
    const Value* meaning = e.get("meaning");
    return meaning && std::holds_alternative<std::string>(*meaning) &&
           std::get<std::string>(*meaning) == "raw_position";
}

}  // namespace

bool isTimingField(const std::string& key) {
    // A moment ("request_start_ns": when the TMCL request began) is not a duration: its
    // spread is only the capture's length.
    if (endsWith(key, "start_ns") || endsWith(key, "end_ns")) return false;
    return endsWith(key, "_ns") || endsWith(key, "_us") || endsWith(key, "_hz") ||
           endsWith(key, "_cycles") || key == "repeats";
}

void PositionTrace::add(double t_ns, double value) {
    if (!points_.empty() && points_.back().n < stride_) {
        auto& p = points_.back();
        p.lo = std::min(p.lo, value);
        p.hi = std::max(p.hi, value);
        ++p.n;
        return;
    }
    if (points_.size() == kMaxPoints) halve();
    if (!points_.empty() && points_.back().n < stride_) {
        add(t_ns, value);
        return;
    }
    points_.push_back(Point{t_ns, value, value, 1});
}

void PositionTrace::halve() {
    std::vector<Point> merged;
    merged.reserve(points_.size() / 2 + 1);
    for (std::size_t i = 0; i < points_.size(); i += 2) {
        Point p = points_[i];
        if (i + 1 < points_.size()) {
            const Point& q = points_[i + 1];
            p.lo = std::min(p.lo, q.lo);
            p.hi = std::max(p.hi, q.hi);
            p.n += q.n;
        }
        merged.push_back(p);
    }
    points_ = std::move(merged);
    stride_ *= 2;
}

QuantileSketch& GroupStats::timingField(const std::string& key) {
    for (auto& [k, s] : timing)
        if (k == key) return s;
    timing.emplace_back(key, QuantileSketch{});
    return timing.back().second;
}

GroupStats::FlagCount& GroupStats::flag(const std::string& key) {
    for (auto& [k, f] : flags)
        if (k == key) return f;
    flags.emplace_back(key, FlagCount{});
    return flags.back().second;
}

void CaptureStats::begin(const CaptureFacts& facts) {
    facts_ = facts;
    for (const auto& p : facts.protos)
        noteInstance(p);
    for (const auto& [instance, options] : facts.options)
        wraps_[instance] = PositionWrap(instance.substr(0, instance.find('#')), options);
    if (keep_waves_) edges_.begin(facts);
}

void TimeCounts::add(double t_ns) {
    if (!started_) {
        origin_ns_ = t_ns;
        started_ = true;
    }
    ++total_;
    std::size_t bin = std::size_t(std::max(0.0, (t_ns - origin_ns_) / bin_ns_));
    while (bin >= kMaxBins) {
        std::vector<std::uint64_t> merged((bins_.size() + 1) / 2, 0);
        for (std::size_t i = 0; i < bins_.size(); ++i)
            merged[i / 2] += bins_[i];
        bins_ = std::move(merged);
        bin_ns_ *= 2;
        bin = std::size_t((t_ns - origin_ns_) / bin_ns_);
    }
    if (bins_.size() <= bin) bins_.resize(bin + 1);
    ++bins_[bin];
}

const TimeCounts* CaptureStats::faultsOverTime(const std::string& instance) const {
    auto it = fault_times_.find(instance);
    return it == fault_times_.end() ? nullptr : &it->second;
}

void CaptureStats::end(const CaptureFacts& facts) {
    facts_ = facts;
}

void CaptureStats::noteInstance(const std::string& instance) {
    if (std::find(instances_.begin(), instances_.end(), instance) == instances_.end())
        instances_.push_back(instance);
}

GroupStats& CaptureStats::group(const Event& e) {
    const std::string& inst = e.instance.empty() ? e.proto : e.instance;
    for (auto& g : groups_)
        if (g.instance == inst && g.type == e.type) return g;
    noteInstance(inst);
    GroupStats g;
    g.instance = inst;
    g.proto = e.proto;
    g.type = e.type;
    groups_.push_back(std::move(g));
    return groups_.back();
}

void CaptureStats::addPause(GroupStats& g, const Event& e) {
    const Value* line = e.get("line");
    const std::string name = line && std::holds_alternative<std::string>(*line)
                                 ? std::get<std::string>(*line)
                                 : std::string();
    auto it = std::find_if(g.line_ends.begin(), g.line_ends.end(),
                           [&](const auto& l) { return l.first == name; });
    if (it == g.line_ends.end()) {
        g.line_ends.emplace_back(name, e.end);
        return;
    }
    // Events that overlap the ones before (the register accesses one control frame
    // sequence carries, spanning the same frames) have no pause between them.
    if (e.start >= it->second) g.pause_ns.add(facts_.timebase.toNsF(double(e.start - it->second)));
    it->second = std::max(it->second, e.end);
}

void CaptureStats::add(const Event& e) {
    const Timebase& tb = facts_.timebase;
    if (signal_.add(e, tb)) return;
    GroupStats& g = group(e);
    if (g.count == 0) g.first_start = e.start;
    addPause(g, e);
    ++g.count;
    ++total_events_;

    for (const auto& f : e.fields) {
        if (isNull(f.value)) continue;
        if (auto b = std::get_if<bool>(&f.value)) {
            auto& c = g.flag(f.key);
            ++(*b ? c.true_count : c.false_count);
        } else if (isActiveLowFlag(f.key) && isNumber(f.value)) {
            auto& c = g.flag(f.key);
            ++(asInt(f.value) == 0 ? c.false_count : c.true_count);
        } else if (isTimingField(f.key) && isNumber(f.value)) {
            g.timingField(f.key).add(asDouble(f.value));
        }
    }

    const std::string& inst = g.instance;
    if (const Value* pos = e.get("position"); pos && isNumber(*pos) && !isGrayWord(e))
        addPosition(inst, e, asDouble(*pos));

    if (e.type == "register") {
        const Value* addr = e.get("address");
        const Value* data = e.get("data");
        auto& regs = registers_[inst];
        if (addr && isNumber(*addr) && (regs.size() < kMaxRegisters || regs.count(asInt(*addr)))) {
            auto& r = regs[asInt(*addr)];
            const Value* op = e.get("op");
            const bool write = op && std::holds_alternative<std::string>(*op) &&
                               std::get<std::string>(*op) == "write";
            ++(write ? r.writes : r.reads);
            if (data && isNumber(*data)) r.last_data = asInt(*data);
            if (const Value* ok = e.get("crc_ok"); ok && !asInt(*ok)) r.crc_failed = true;
        }
    }

    if (keep_waves_) edges_.offer(e);
    if (!e.errors.empty()) {
        fault_times_[inst].add(tb.toNsF(double(e.start)));
        ++g.faulty;
        ++total_faults_;
        for (const auto& err : e.errors)
            ++g.errors[err];
        if (faults_.size() < kMaxFaults) faults_.push_back({e.start, inst, eventToText(e, tb)});
        if (!first_faulty_) first_faulty_ = e;
    }
}

void CaptureStats::addPosition(const std::string& inst, const Event& e, double v) {
    const double t_ns = facts_.timebase.toNsF(double(e.start));
    auto& p = positions_[inst];
    auto wrap = wraps_.find(inst);
    p.modulus = wrap == wraps_.end() ? 0 : wrap->second.modulus(e);
    if (p.count == 0) {
        p.min = p.max = p.unwrapped = v;
    } else {
        p.min = std::min(p.min, v);
        p.max = std::max(p.max, v);
        const double step = shortestDifference(p.last, v, p.modulus);
        if (std::fabs(step) > p.max_jump) {
            p.max_jump = std::fabs(step);
            p.max_jump_at = e.start;
        }
        p.unwrapped += step;
        if (t_ns > p.last_t_ns) p.velocity.add(t_ns, step * 1e9 / (t_ns - p.last_t_ns));
    }
    p.last = v;
    p.last_t_ns = t_ns;
    ++p.count;
    p.trace.add(t_ns, p.unwrapped);
}

std::vector<const GroupStats*> CaptureStats::groupsOf(const std::string& instance) const {
    std::vector<const GroupStats*> out;
    for (const auto& g : groups_)
        if (g.instance == instance) out.push_back(&g);
    return out;
}

const PositionStats* CaptureStats::position(const std::string& instance) const {
    auto it = positions_.find(instance);
    return it == positions_.end() ? nullptr : &it->second;
}

const std::map<std::int64_t, RegisterStats>* CaptureStats::registers(
    const std::string& instance) const {
    auto it = registers_.find(instance);
    return it == registers_.end() ? nullptr : &it->second;
}

}  // namespace busdecode
