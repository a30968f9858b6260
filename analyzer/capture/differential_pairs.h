#pragma once
// Differential pairs (RS-422: MA+/MA-): `--map ma=MA+,MA-` decodes one line from two
// wires. A PairWatch follows the two wires' levels and reports every stretch where they
// stop being complementary (one wire open, shorted or stuck) as a pair fault, naming the
// wire that stopped following, and tells which wire still works. pairedReader() adds
// such lines to a capture of logic lines (the positive wire decodes, or the inverted
// negative one while the positive is at fault); analog captures take the difference of
// the two voltages instead (analog_capture.h).
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "capture_reader.h"

namespace busdecode {

// What the data tells of a fault: a wire that stays put (stuck; open when an analog
// wire sits between its two levels), or both wires moving together (shorted).
enum class PairFaultKind { Stuck, Open, Shorted };
const char* pairFaultKindName(PairFaultKind k);

struct PairFault {
    Tick start = 0, end = 0;
    int wire = 0;  // the wire that stopped following: 0 positive, 1 negative
    PairFaultKind kind = PairFaultKind::Stuck;
};

class PairWatch {
public:
    // Stretches of equal levels up to `grace` ticks are skew between the wires, not faults.
    explicit PairWatch(Tick grace) : grace_(grace) {}
    void start(Tick t, std::uint8_t p, std::uint8_t n);
    // True when this edge shows a fault that began earlier (stuckWire() names its wire).
    bool edge(Tick t, int wire, std::uint8_t level);
    void finish(Tick t);
    // An analog reader's finding when the fault opened: the stuck wire sits midway.
    void markOpen() { open_ = true; }
    int stuckWire() const { return stuck(); }
    // Faults closed since the last call, for events of their own.
    void takeClosed(std::vector<PairFault>& out) {
        out.insert(out.end(), closed_.begin(), closed_.end());
        closed_.clear();
    }
    // The start of a fault still open, or of a stretch of equal levels that may become
    // one; kNoTick when the wires are complementary.
    Tick pendingFrom() const { return in_fault_ ? fault_start_ : equal_since_; }
    // The wire to decode from: 0 unless the positive one is at fault.
    int working() const { return in_fault_ && stuck() == 0 ? 1 : 0; }
    const std::vector<PairFault>& faults() const { return faults_; }
    std::uint64_t faultCount() const { return count_; }

private:
    int stuck() const { return fault_edges_[0] < fault_edges_[1] ? 0 : 1; }
    void closeFault(Tick end);
    bool openFault();

    Tick grace_;
    std::uint8_t level_[2] = {0, 1};
    Tick equal_since_ = kNoTick;
    bool in_fault_ = false;
    Tick fault_start_ = 0, last_bad_ = 0;
    std::uint64_t fault_edges_[2] = {0, 0}, clean_edges_[2] = {0, 0};
    bool open_ = false;
    std::vector<PairFault> faults_;  // the first kKeptFaults
    std::vector<PairFault> closed_;  // not yet taken
    std::uint64_t count_ = 0;
    static constexpr std::size_t kKeptFaults = 1000;
};

// "MA+,MA-" -> the two signal texts (names or indices); false if `text` is not a pair.
bool splitPair(const std::string& text, std::string& positive, std::string& negative);

// Index of `text` (a name, full name or 0-based index) in `signals`, or -1.
int findSignal(const std::vector<SignalInfo>& signals, const std::string& text);

// Notes for the summary about a pair's faults.
std::vector<std::string> pairFaultNotes(const std::string& pair, const PairWatch& watch,
                                        const Timebase& tb);

// The `pair_fault` event of `f` on the pair named `pair` ("MA+,MA-").
Event pairFaultEvent(const std::string& pair, const PairFault& f);

// Moves the faults `watch` closed into `block` as events, and holds the block's findings
// back to the start of one still open.
void addPairFindings(const std::string& pair, PairWatch& watch, EdgeBlock& block);

// Adds a signal per pair of OpenOptions::pairs that `inner` does not have already.
std::unique_ptr<CaptureReader> pairedReader(std::unique_ptr<CaptureReader> inner,
                                            const std::vector<std::string>& pairs);

}  // namespace busdecode
