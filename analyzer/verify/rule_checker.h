#pragma once
// Checks one capture's events against the rules while they stream by (an OutputSink, so
// it runs in the same pass as any other sink): each rule keeps a counter or a running
// extreme and the time of its first offending event, nothing more.
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/session.h"
#include "rules.h"

namespace busdecode {

struct RuleOutcome {
    std::string proto;  // the rules table
    std::string rule;   // "max_crc_errors", "registers.0x78", ...
    bool passed = true;
    std::string message;  // what was seen, and where the first offence was
    // When the rule failed: the first offending event, or for a count limit above 0 the
    // event that passed the limit (JUnit and the verdict line give this time too).
    std::optional<double> first_ns;
    std::uint64_t offending = 0;  // how many events broke the rule
    std::string name() const { return proto + "." + rule; }
};

class RuleCheck {
public:
    virtual ~RuleCheck() = default;
    virtual void begin(const CaptureFacts& facts) { (void)facts; }
    virtual void observe(const Event& e, const Timebase& tb) = 0;
    virtual RuleOutcome finish(const CaptureFacts& facts) const = 0;
};

class RuleChecker : public OutputSink {
public:
    explicit RuleChecker(const Rules& rules);
    ~RuleChecker() override;
    void begin(const CaptureFacts& facts) override;
    void onEvent(const Event& e, const CaptureFacts& facts) override;
    void end(const CaptureFacts& facts) override;
    bool readsSummaries() const override { return false; }  // rules check fields

    // One outcome per rule, in rules-file order (valid after end()).
    const std::vector<RuleOutcome>& outcomes() const { return outcomes_; }
    // "bissc 1000 frames, ssi 20 frames": what the capture held, for the PASS line.
    std::string eventSummary() const;

private:
    struct Table {
        std::string proto;
        std::string primary_type;
        std::uint64_t events = 0, primary = 0;
        std::vector<std::unique_ptr<RuleCheck>> checks;
    };
    std::vector<Table> tables_;
    std::vector<RuleOutcome> outcomes_;
    Timebase tb_;
};

}  // namespace busdecode
