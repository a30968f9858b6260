#include "rule_checker.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "report/position_wrap.h"
#include "report/report_format.h"
#include "sinks/event_format.h"

namespace busdecode {

namespace {

bool isNumber(const Value* v) {
    return v &&
           (std::holds_alternative<std::int64_t>(*v) || std::holds_alternative<std::uint64_t>(*v) ||
            std::holds_alternative<double>(*v) || std::holds_alternative<bool>(*v));
}

RuleOutcome makeOutcome(const std::string& proto, const std::string& rule) {
    RuleOutcome o;
    o.proto = proto;
    o.rule = rule;
    return o;
}

std::string at(double ns) {
    return formatDuration(ns);
}

std::string plural(std::uint64_t n, const std::string& one, const std::string& many) {
    return fmt::format("{} {}", n, n == 1 ? one : many);
}

// "at most `limit` events may match": counts matches, remembers the first and the one
// that went over the limit.
class CountCheck : public RuleCheck {
public:
    using Pred = std::function<bool(const Event&)>;
    // `one` / `many`: what is counted, for 1 and for other counts.
    // `field`: one the decoder must carry for the rule to mean anything ("": none).
    CountCheck(std::string proto, std::string rule, std::int64_t limit, std::string one,
               std::string many, Pred pred, std::string field = "")
        : proto_(std::move(proto)),
          rule_(std::move(rule)),
          limit_(limit),
          one_(std::move(one)),
          many_(std::move(many)),
          pred_(std::move(pred)),
          field_(std::move(field)) {}
    void observe(const Event& e, const Timebase& tb) override {
        carried_ = carried_ || (!field_.empty() && e.get(field_));
        if (!pred_(e)) return;
        ++count_;
        const double t = double(tb.toNs(e.start));
        if (count_ == 1) first_ = t;
        if (count_ == std::uint64_t(limit_) + 1) over_ = t;
    }
    RuleOutcome finish(const CaptureFacts&) const override {
        RuleOutcome o = makeOutcome(proto_, rule_);
        o.offending = count_;
        o.passed = count_ <= std::uint64_t(limit_);
        if (count_ == 0 && !field_.empty() && !carried_) {  // BiSS-C has no repeats to match
            o.message = fmt::format("not checked: no event carries {}", field_);
            return o;
        }
        o.message = fmt::format("{} (limit {})", plural(count_, one_, many_), limit_);
        if (count_) {
            o.message += fmt::format(", first at {}", at(first_));
            if (!o.passed) o.first_ns = limit_ == 0 ? first_ : over_;
            if (!o.passed && limit_ > 0)
                o.message += fmt::format(", limit passed at {}", at(over_));
        }
        return o;
    }

private:
    std::string proto_, rule_;
    std::int64_t limit_;
    std::string one_, many_;
    Pred pred_;
    std::string field_;
    bool carried_ = false;
    std::uint64_t count_ = 0;
    double first_ = 0, over_ = 0;
};

// max_faults: events with any error, and which errors they were, most frequent first
// ("by kind: short_frame 126, crc 2"): a failed capture says what went wrong without a
// second run of `decode`.
class FaultCheck : public CountCheck {
public:
    FaultCheck(std::string proto, std::string rule, std::int64_t limit)
        : CountCheck(std::move(proto), std::move(rule), limit, "event with errors",
                     "events with errors", [](const Event& e) { return !e.errors.empty(); }) {}
    void observe(const Event& e, const Timebase& tb) override {
        CountCheck::observe(e, tb);
        for (const auto& err : e.errors) {
            auto it = kinds_.find(err);
            if (it != kinds_.end())
                ++it->second;
            else if (kinds_.size() < kMaxKinds)
                kinds_.emplace(err, 1);
            else
                ++other_;
        }
    }
    RuleOutcome finish(const CaptureFacts& facts) const override {
        RuleOutcome o = CountCheck::finish(facts);
        if (kinds_.empty()) return o;
        std::vector<std::pair<std::string, std::uint64_t>> kinds(kinds_.begin(), kinds_.end());
        std::stable_sort(kinds.begin(), kinds.end(),
                         [](const auto& a, const auto& b) { return a.second > b.second; });
        o.message += "; by kind:";
        for (std::size_t i = 0; i < kinds.size(); ++i)
            o.message += fmt::format("{} {} {}", i ? "," : "", kinds[i].first, kinds[i].second);
        if (other_) o.message += fmt::format(", others {}", other_);
        return o;
    }

private:
    // Decoders name their errors from a small fixed set; a plugin that made up new ones
    // without end would still not grow the map past this.
    static constexpr std::size_t kMaxKinds = 64;
    std::map<std::string, std::uint64_t> kinds_;
    std::uint64_t other_ = 0;
};

// Every value of `field` (times `scale`) must lie in [min, max].
class RangeCheck : public RuleCheck {
public:
    RangeCheck(std::string proto, std::string rule, std::string field, double scale, double min,
               double max, std::string unit_key)
        : proto_(std::move(proto)),
          rule_(std::move(rule)),
          field_(std::move(field)),
          scale_(scale),
          min_(min),
          max_(max),
          unit_key_(std::move(unit_key)) {}
    void observe(const Event& e, const Timebase& tb) override {
        const Value* v = e.get(field_);
        if (!isNumber(v)) return;  // absent or null (e.g. tm_ns when the capture ended)
        const double x = asDouble(*v) * scale_;
        if (!std::isfinite(x)) return;
        if (seen_ == 0) lo_ = hi_ = x;
        lo_ = std::min(lo_, x);
        hi_ = std::max(hi_, x);
        ++seen_;
        if (x < min_ || x > max_) {
            if (bad_ == 0) {
                first_ = double(tb.toNs(e.start));
                first_value_ = x;
            }
            ++bad_;
        }
    }
    RuleOutcome finish(const CaptureFacts&) const override {
        RuleOutcome o = makeOutcome(proto_, rule_);
        o.offending = bad_;
        o.passed = bad_ == 0;
        if (seen_ == 0) {
            o.message = fmt::format("not checked: no event carries {}", field_);
            return o;
        }
        o.message = fmt::format("{} of {} {} (seen {} .. {})", bad_,
                                plural(seen_, "value", "values"), limits(), fmtv(lo_), fmtv(hi_));
        if (bad_) {
            o.first_ns = first_;
            o.message += fmt::format(", first at {} ({})", at(first_), fmtv(first_value_));
        }
        return o;
    }

private:
    std::string fmtv(double v) const { return formatFieldValue(unit_key_, v); }
    std::string limits() const {
        if (min_ == -std::numeric_limits<double>::infinity()) return "above " + fmtv(max_);
        if (max_ == std::numeric_limits<double>::infinity()) return "below " + fmtv(min_);
        return fmt::format("outside [{}, {}]", fmtv(min_), fmtv(max_));
    }
    std::string proto_, rule_, field_;
    double scale_, min_, max_;
    std::string unit_key_;
    std::uint64_t seen_ = 0, bad_ = 0;
    double lo_ = 0, hi_ = 0, first_ = 0, first_value_ = 0;
};

class MinCountCheck : public RuleCheck {
public:
    MinCountCheck(std::string proto, std::string type, std::int64_t min)
        : proto_(std::move(proto)), type_(std::move(type)), min_(min) {}
    void observe(const Event& e, const Timebase&) override {
        if (type_.empty() || e.type == type_) ++count_;
    }
    RuleOutcome finish(const CaptureFacts&) const override {
        RuleOutcome o = makeOutcome(proto_, "min_frames");
        o.passed = count_ >= std::uint64_t(min_);
        const std::string noun = type_.empty() ? "event" : type_;
        o.message = fmt::format("{} (minimum {})", plural(count_, noun, noun + "s"), min_);
        return o;
    }

private:
    std::string proto_, type_;
    std::int64_t min_;
    std::uint64_t count_ = 0;
};

// Consecutive positions of one decoder instance may differ by at most `max`, taken the
// short way round where the position wraps (position_wrap.h).
class JumpCheck : public RuleCheck {
public:
    JumpCheck(std::string proto, double max, std::optional<double> modulus)
        : proto_(std::move(proto)), max_(max), modulus_(modulus) {}
    void begin(const CaptureFacts& facts) override {
        for (const auto& [instance, options] : facts.options)
            lines_[instance].wrap = PositionWrap(decoderOf(instance), options, modulus_);
    }
    void observe(const Event& e, const Timebase& tb) override {
        const Value* v = e.get("position");
        if (!isNumber(v)) return;
        const double p = asDouble(*v);
        auto it = lines_.find(e.instance);
        if (it == lines_.end())
            it = lines_.emplace(e.instance, Line{PositionWrap(e.proto, {}, modulus_)}).first;
        Line& line = it->second;
        if (line.have_last) {
            const double jump = std::fabs(line.wrap.difference(line.last, p, e));
            largest_ = std::max(largest_, jump);
            if (jump > max_) {
                if (bad_ == 0) {
                    first_ = double(tb.toNs(e.start));
                    first_jump_ = jump;
                    from_ = line.last;
                    to_ = p;
                }
                ++bad_;
            }
        }
        line.last = p;
        line.have_last = true;
    }
    RuleOutcome finish(const CaptureFacts&) const override {
        RuleOutcome o = makeOutcome(proto_, "max_position_jump");
        o.offending = bad_;
        o.passed = bad_ == 0;
        o.message = fmt::format("{} (limit {:.0f}, largest {:.0f})", plural(bad_, "jump", "jumps"),
                                max_, largest_);
        if (bad_) {
            o.first_ns = first_;
            o.message += fmt::format(", first at {} ({:.0f} -> {:.0f}, jump {:.0f})", at(first_),
                                     from_, to_, first_jump_);
        }
        return o;
    }

private:
    // "bissc#2" -> "bissc": instance names are the decoder id, numbered when repeated.
    static std::string decoderOf(const std::string& instance) {
        return instance.substr(0, instance.find('#'));
    }
    struct Line {
        PositionWrap wrap;
        bool have_last = false;
        double last = 0;
    };
    std::string proto_;
    double max_;
    std::optional<double> modulus_;
    std::map<std::string, Line> lines_;  // per decoder instance
    double largest_ = 0, first_ = 0, first_jump_ = 0, from_ = 0, to_ = 0;
    std::uint64_t bad_ = 0;
};

class RegisterCheck : public RuleCheck {
public:
    RegisterCheck(std::string proto, std::int64_t address, std::int64_t expected)
        : proto_(std::move(proto)), address_(address), expected_(expected) {}
    void observe(const Event& e, const Timebase& tb) override {
        if (e.type != "register") return;
        const Value* a = e.get("address");
        const Value* d = e.get("data");
        if (!isNumber(a) || asInt(*a) != address_ || !isNumber(d)) return;
        ++seen_;
        if (asInt(*d) != expected_) {
            if (bad_ == 0) {
                first_ = double(tb.toNs(e.start));
                got_ = asInt(*d);
            }
            ++bad_;
        }
    }
    RuleOutcome finish(const CaptureFacts&) const override {
        RuleOutcome o = makeOutcome(proto_, fmt::format("registers.0x{:02X}", address_));
        o.offending = bad_;
        if (seen_ == 0) {
            o.passed = false;
            o.message = fmt::format("register 0x{:02X} never accessed (expected 0x{:02X})",
                                    address_, expected_);
        } else if (bad_) {
            o.passed = false;
            o.first_ns = first_;
            o.message =
                fmt::format("{} of {} with data other than 0x{:02X}, first at {} (0x{:02X})", bad_,
                            plural(seen_, "access", "accesses"), expected_, at(first_), got_);
        } else {
            o.message =
                fmt::format("{} with 0x{:02X}", plural(seen_, "access", "accesses"), expected_);
        }
        return o;
    }

private:
    std::string proto_;
    std::int64_t address_, expected_;
    std::uint64_t seen_ = 0, bad_ = 0;
    double first_ = 0;
    std::int64_t got_ = 0;
};

bool fieldIsZero(const Event& e, std::string_view key) {
    const Value* v = e.get(key);
    return isNumber(v) && asInt(*v) == 0;
}

bool crcFailed(const Event& e) {
    return e.hasError("crc") || fieldIsZero(e, "crc_ok");
}

void addChecks(const ProtoRules& r, std::vector<std::unique_ptr<RuleCheck>>& out) {
    const std::string& p = r.proto;
    constexpr double kInf = std::numeric_limits<double>::infinity();
    for (const auto& key : r.keys) {
        if (key == "max_crc_errors")
            out.push_back(std::make_unique<CountCheck>(p, key, *r.max_crc_errors,
                                                       "event with a CRC error",
                                                       "events with CRC errors", crcFailed));
        else if (key == "max_errors")
            out.push_back(std::make_unique<CountCheck>(
                p, key, *r.max_errors, "frame with nE active", "frames with nE active",
                [](const Event& e) { return fieldIsZero(e, "nE"); }, "nE"));
        else if (key == "max_warnings")
            out.push_back(std::make_unique<CountCheck>(
                p, key, *r.max_warnings, "frame with nW active", "frames with nW active",
                [](const Event& e) { return fieldIsZero(e, "nW"); }, "nW"));
        else if (key == "max_repeat_mismatches")
            out.push_back(std::make_unique<CountCheck>(
                p, key, *r.max_repeat_mismatches, "repeat mismatch", "repeat mismatches",
                [](const Event& e) {
                    return e.hasError("repeat_mismatch") || fieldIsZero(e, "repeat_match");
                },
                "repeat_match"));
        else if (key == "max_faults")
            out.push_back(std::make_unique<FaultCheck>(p, key, *r.max_faults));
        else if (key == "min_frames")
            out.push_back(std::make_unique<MinCountCheck>(p, primaryEventType(p), *r.min_frames));
        else if (key == "clock_hz")
            out.push_back(std::make_unique<RangeCheck>(p, key, "clock_hz", 1.0, r.clock_hz->min,
                                                       r.clock_hz->max, "clock_hz"));
        else if (key == "max_line_delay_ns")
            out.push_back(std::make_unique<RangeCheck>(p, key, "line_delay_ns", 1.0, -kInf,
                                                       *r.max_line_delay_ns, "line_delay_ns"));
        else if (key == "max_proc_cycles")
            out.push_back(std::make_unique<RangeCheck>(p, key, "proc_cycles", 1.0, -kInf,
                                                       *r.max_proc_cycles, "proc_cycles"));
        else if (key == "tm_us")
            out.push_back(std::make_unique<RangeCheck>(p, key, "tm_ns", 1e-3, r.tm_us->min,
                                                       r.tm_us->max, "tm_us"));
        else if (key == "timeout_us")
            out.push_back(std::make_unique<RangeCheck>(
                p, key, "timeout_ns", 1e-3, r.timeout_us->min, r.timeout_us->max, "timeout_us"));
        else if (key == "position")
            out.push_back(std::make_unique<RangeCheck>(p, key, "position", 1.0, r.position->min,
                                                       r.position->max, "position"));
        else if (key == "max_position_jump")
            out.push_back(std::make_unique<JumpCheck>(p, *r.max_position_jump, r.position_modulus));
        else if (key == "registers")
            for (const auto& [addr, value] : r.registers)
                out.push_back(std::make_unique<RegisterCheck>(p, addr, value));
        else if (key == "min_swing_v")
            out.push_back(std::make_unique<RangeCheck>(p, key, "swing_v", 1.0, *r.min_swing_v, kInf,
                                                       "swing_v"));
        else if (key == "max_rise_ns")
            out.push_back(std::make_unique<RangeCheck>(p, key, "rise_p99_ns", 1.0, -kInf,
                                                       *r.max_rise_ns, "rise_p99_ns"));
        else if (key == "max_fall_ns")
            out.push_back(std::make_unique<RangeCheck>(p, key, "fall_p99_ns", 1.0, -kInf,
                                                       *r.max_fall_ns, "fall_p99_ns"));
        else if (key == "max_overshoot_pct")
            out.push_back(std::make_unique<RangeCheck>(p, key, "overshoot_pct", 1.0, -kInf,
                                                       *r.max_overshoot_pct, "overshoot_pct"));
    }
}

}  // namespace

RuleChecker::RuleChecker(const Rules& rules) {
    for (const auto& r : rules.tables) {
        Table t;
        t.proto = r.proto;
        t.primary_type = primaryEventType(r.proto);
        addChecks(r, t.checks);
        tables_.push_back(std::move(t));
    }
}

RuleChecker::~RuleChecker() = default;

void RuleChecker::begin(const CaptureFacts& facts) {
    tb_ = facts.timebase;
    for (auto& t : tables_)
        for (auto& c : t.checks)
            c->begin(facts);
}

void RuleChecker::onEvent(const Event& e, const CaptureFacts&) {
    for (auto& t : tables_) {
        // A table names a decoder id, or one instance when the same decoder runs twice.
        if (t.proto == kSignalTable ? e.proto != "capture" || e.type != "signal"
                                    : e.proto != t.proto && e.instance != t.proto)
            continue;
        ++t.events;
        if (t.primary_type.empty() || e.type == t.primary_type) ++t.primary;
        for (auto& c : t.checks)
            c->observe(e, tb_);
    }
}

void RuleChecker::end(const CaptureFacts& facts) {
    outcomes_.clear();
    for (const auto& t : tables_)
        for (const auto& c : t.checks)
            outcomes_.push_back(c->finish(facts));
}

std::string RuleChecker::eventSummary() const {
    std::string s;
    for (const auto& t : tables_) {
        const std::string noun = t.primary_type.empty() ? "event" : t.primary_type;
        s += fmt::format("{}{} {}", s.empty() ? "" : ", ", t.proto,
                         plural(t.primary, noun, noun + "s"));
    }
    return s;
}

}  // namespace busdecode
