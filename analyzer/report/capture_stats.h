#pragma once
// Everything a report says about one decode pass, gathered while the events stream by:
// no event is kept (except the first faulty one, for its picture), no second pass, and
// memory stays bounded whatever the capture length (sketches, capped tables, a
// decimated position trace).
//
// The statistics are generic: they work from the field names present in the events, per
// decoder instance and event type. Numeric fields whose names end in `_ns`, `_us`, `_hz`
// or `_cycles` (and `repeats`) get min / median / p99 / max; bool fields count their
// false values; `nE` / `nW` count active (0) bits; `position` gets its range, largest
// jump and a trace over time; `register` events with `address` and `data` fill a
// register table.
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/event.h"
#include "core/session.h"
#include "edge_window.h"
#include "position_wrap.h"
#include "quantile_sketch.h"
#include "signal_section.h"

namespace busdecode {

// Position over time with at most kMaxPoints points: when full, neighbouring points are
// merged (keeping their min and max, so spikes stay visible) and the stride doubles.
class PositionTrace {
public:
    static constexpr std::size_t kMaxPoints = 1024;
    struct Point {
        double t_ns;  // time of the first event in the point
        double lo, hi;
        std::uint64_t n;
    };
    void add(double t_ns, double value);
    const std::vector<Point>& points() const { return points_; }

private:
    void halve();
    std::vector<Point> points_;
    std::uint64_t stride_ = 1;  // events per point
};

struct GroupStats {
    std::string instance, proto, type;
    std::uint64_t count = 0;
    std::uint64_t faulty = 0;  // events with a non-empty `errors`
    std::map<std::string, std::uint64_t> errors;
    // Timing-like numeric fields, in first-seen order.
    std::vector<std::pair<std::string, QuantileSketch>> timing;
    // Bool fields: how many events had them false / true. nE and nW count active (= 0).
    struct FlagCount {
        std::uint64_t false_count = 0, true_count = 0;
    };
    std::vector<std::pair<std::string, FlagCount>> flags;
    // From the end of the events so far to the start of the next on the same line (a
    // UART's rx and tx each have their own), for events that start after that end
    // (overlapping events have no pause between them).
    QuantileSketch pause_ns;
    Tick first_start = 0;
    // The latest end so far on each line (the event's `line` field; "" without one).
    std::vector<std::pair<std::string, Tick>> line_ends;

    QuantileSketch& timingField(const std::string& key);
    FlagCount& flag(const std::string& key);
    // The rows of its timing table, as both reports print it: each timed field, then the
    // pause between events if there was one.
    std::vector<std::pair<std::string, const QuantileSketch*>> timingRows() const {
        std::vector<std::pair<std::string, const QuantileSketch*>> rows;
        for (const auto& [k, s] : timing)
            rows.emplace_back(k, &s);
        if (!pause_ns.empty()) rows.emplace_back("pause_ns", &pause_ns);
        return rows;
    }
};

struct PositionStats {
    std::uint64_t count = 0;
    double min = 0, max = 0;
    double last = 0;
    double modulus = 0;   // where the position wraps (0: it does not), from the last event
    double max_jump = 0;  // largest |difference| between consecutive positions, the short way
    Tick max_jump_at = 0;
    // The position unwrapped (first value plus the short-way differences since), so that a
    // rollover draws as the motion it is; and counts per second between frames.
    double unwrapped = 0;
    double last_t_ns = 0;
    PositionTrace trace;
    PositionTrace velocity;
};

// Events with errors over time in at most kMaxBins bins: when the capture outgrows them,
// neighbouring bins merge and the bin width doubles.
class TimeCounts {
public:
    static constexpr std::size_t kMaxBins = 200;
    void add(double t_ns);
    double binNs() const { return bin_ns_; }
    double originNs() const { return origin_ns_; }
    const std::vector<std::uint64_t>& bins() const { return bins_; }
    std::uint64_t total() const { return total_; }

private:
    double origin_ns_ = 0, bin_ns_ = 1000;
    bool started_ = false;
    std::vector<std::uint64_t> bins_;
    std::uint64_t total_ = 0;
};

struct RegisterStats {
    std::uint64_t reads = 0, writes = 0;
    std::int64_t last_data = 0;
    bool crc_failed = false;
};

struct FaultRecord {
    Tick start = 0;
    std::string instance;
    std::string text;  // the event as one human line (eventToText)
};

class CaptureStats {
public:
    static constexpr std::size_t kMaxFaults = 10;
    static constexpr std::size_t kMaxRegisters = 256;  // per instance

    void begin(const CaptureFacts& facts);
    void add(const Event& e);
    void end(const CaptureFacts& facts);

    const CaptureFacts& facts() const { return facts_; }
    // Instances in first-seen order (--proto order first).
    const std::vector<std::string>& instances() const { return instances_; }
    std::vector<const GroupStats*> groupsOf(const std::string& instance) const;
    const PositionStats* position(const std::string& instance) const;
    const std::map<std::int64_t, RegisterStats>* registers(const std::string& instance) const;
    std::uint64_t totalEvents() const { return total_events_; }
    std::uint64_t totalFaults() const { return total_faults_; }
    const std::vector<FaultRecord>& firstFaults() const { return faults_; }
    const std::optional<Event>& firstFaultyEvent() const { return first_faulty_; }
    // Faulty events over time, per instance (null when it had none).
    const TimeCounts* faultsOverTime(const std::string& instance) const;
    // The captured waveforms of the first faulty events and a clean one per type (only
    // when the sink hands the edges over: addEdges()).
    void addEdges(const Edge* first, const Edge* last) { edges_.addEdges(first, last); }
    void addVolts(const std::vector<VoltSample>& volts,
                  const std::vector<LineThreshold>& thresholds) {
        edges_.addVolts(volts, thresholds);
    }
    void keepWaveforms(bool on) { keep_waves_ = on; }
    const std::vector<FrameWave>& waveforms() const { return edges_.waves(); }
    // Analog lines' signal quality and pair faults (the capture layer's events).
    const SignalSection& signalSection() const { return signal_; }

private:
    GroupStats& group(const Event& e);
    void noteInstance(const std::string& instance);
    void addPosition(const std::string& inst, const Event& e, double value);
    void addPause(GroupStats& g, const Event& e);

    CaptureFacts facts_;
    SignalSection signal_;
    std::vector<std::string> instances_;
    std::vector<GroupStats> groups_;  // few (instances x types): linear search is fine
    std::map<std::string, PositionStats> positions_;
    std::map<std::string, PositionWrap> wraps_;  // per instance, from its options
    std::map<std::string, std::map<std::int64_t, RegisterStats>> registers_;
    std::vector<FaultRecord> faults_;
    std::optional<Event> first_faulty_;
    std::map<std::string, TimeCounts> fault_times_;
    EdgeWindows edges_;
    bool keep_waves_ = false;
    std::uint64_t total_events_ = 0, total_faults_ = 0;
};

// Field names the statistics treat as timing values.
bool isTimingField(const std::string& key);

}  // namespace busdecode
