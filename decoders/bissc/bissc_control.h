#pragma once
// BiSS-C control communication: one CDM bit (master, in the timeout) and one CDS bit
// (slave, after the start bit) per BiSS frame add up, over many frames, to register
// accesses and commands. This class sees only those two bits per frame, in frame order,
// and emits `register` / `command` events spanning the frames that carried them.
//
// Frame index f counts from the frame whose CDM is the control start bit S (f = 0); the
// slave answers CDM(f) with CDS(f+1). Register access (CTS = 1), docs/protocols.md §1.4:
//   CDM: S CTS ID2..0 ADR6..0 CRC3..0 R W S [S repeated while the slave is busy]
//        then DATA7..0 CRC3..0 P (write) or twelve 0s and P (read); S again = sequential.
//   CDS: IDL at f1.., R W echo at f17/f18, then S, DATA7..0, CRC3..0, P one frame later.
// Command (CTS = 0): S CTS IDS0..7 CMD1..0 CRC3..0 S, IDA0..7 on CDS, then EX on CDM
// (or 14 zeros: cancelled).
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "core/event.h"
#include "core/time.h"

namespace busdecode {

struct ControlBits {
    Tick start = 0;  // the BiSS frame that carried the bits
    Tick end = 0;
    int cdm = -1;  // decoded CDM bit (inverted MA level in the timeout); -1 unknown
    int cds = -1;  // CDS bit; -1 unknown (frame broken)
};

class BisscControlReassembler {
public:
    using Emit = std::function<void(Event&&)>;
    explicit BisscControlReassembler(Emit emit) : emit_(std::move(emit)) {}

    void push(const ControlBits& frame);
    // Capture ended: an access still open is reported with what was seen (short_frame).
    void finish();
    // Start of the earliest frame of an access still open (its event will start there),
    // or kNoTick when nothing is open.
    Tick openSince() const;
    // For BisscDecoder::spliceState(): false while an access is open (its frames' bits
    // would have to be compared too); else appends what decides the next frames' fate.
    bool appendSpliceWords(std::vector<std::uint64_t>& words) const;
    // Idle with the preamble seen (BisscDecoder::guessHistory()).
    void assumePreambleSeen() {
        if (phase_ == Phase::Idle) zeros_ = kPreambleZeros;
    }

    // Needed before a control start bit counts (docs/protocols.md §1.4).
    static constexpr int kPreambleZeros = 14;

private:
    enum class Phase { Idle, Header, WaitSlaveStart, Payload, Command };

    void startAccess(const ControlBits& frame);
    // push()'s steps: outside an access (the preamble, an access's start), and in its
    // header (a register access or a command).
    void pushIdle(const ControlBits& frame);
    void pushHeader(const ControlBits& frame, int f);
    void parseRegisterHeader();
    void emitRegister(bool complete, const char* error);
    // emitRegister()'s steps: a complete access's data byte, its CRCs, echo and stop bits
    // checked (faults added to `e`); and its summary.
    Value checkRegisterPayload(Event& e, bool& crc_ok, bool& refused) const;
    std::string registerSummary(const char* op, const Value& data, bool refused, bool crc_ok) const;
    void emitCommand(bool executed, const char* error);
    void toIdle(int zeros);
    std::uint32_t cdmBits(int from, int n) const;  // n CDM bits from frame `from`, MSB first
    std::uint32_t cdsBits(int from, int n) const;
    int lastIndex() const { return int(frames_.size()) - 1; }

    Emit emit_;
    Phase phase_ = Phase::Idle;
    int zeros_ = 0;  // consecutive CDM zeros seen while idle

    // The access in progress: every frame since its S.
    std::vector<ControlBits> frames_;
    int cts_ = 0;
    // Register access header (valid from WaitSlaveStart on).
    int id_ = 0, address_ = 0, rw_ = 0, rw_echo_ = 0, idl_ = 0;
    bool header_crc_ok_ = true;
    bool header_parsed_ = false;
    // Current byte of a (possibly sequential) access.
    int byte_index_ = 0;
    int s_from_ = 0;       // frame of the master's S for this byte
    int slave_start_ = 0;  // frame of the slave's S (fs)
    int busy_ = 0;         // master S repeats before the slave's S
    // Command.
    int command_zero_run_ = 0;
};

}  // namespace busdecode
