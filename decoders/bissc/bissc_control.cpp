#include "bissc_control.h"

#include <algorithm>

#include <fmt/format.h>

#include "core/crc.h"

namespace busdecode {

namespace {

// Frames of a register access before the slave's answer can start (S at f = 18).
constexpr int kMasterStartFrame = 18;
// Command frame: S at f = 16, then up to this many frames until EX (C6: 8, D2: 7 cycles,
// plus the IDA bits; accept anything before the 14-zero cancel).
constexpr int kCommandStartFrame = 16;
// A slave may stay busy for up to 20 ms; far beyond that the master has given up.
constexpr int kMaxBusyFrames = 100000;

}  // namespace

Tick BisscControlReassembler::openSince() const {
    if (phase_ == Phase::Idle || frames_.empty()) return kNoTick;
    if (byte_index_ > 0) return frames_[s_from_].start;
    return frames_.front().start;
}

std::uint32_t BisscControlReassembler::cdmBits(int from, int n) const {
    std::uint32_t v = 0;
    for (int i = 0; i < n; ++i)
        v = (v << 1) | std::uint32_t(frames_[from + i].cdm & 1);
    return v;
}

std::uint32_t BisscControlReassembler::cdsBits(int from, int n) const {
    std::uint32_t v = 0;
    for (int i = 0; i < n; ++i)
        v = (v << 1) | std::uint32_t(frames_[from + i].cds & 1);
    return v;
}

bool BisscControlReassembler::appendSpliceWords(std::vector<std::uint64_t>& words) const {
    if (phase_ != Phase::Idle || !frames_.empty()) return false;
    // Idle, only the run of CDM zeros counts, and only up to the preamble's length: any
    // run at least that long starts an access at the next CDM = 1 alike. The rest is
    // set afresh when an access starts (startAccess()).
    words.push_back(std::uint64_t(std::min(zeros_, kPreambleZeros)));
    return true;
}

void BisscControlReassembler::toIdle(int zeros) {
    phase_ = Phase::Idle;
    zeros_ = zeros;
    frames_.clear();
    header_parsed_ = false;
    byte_index_ = 0;
}

void BisscControlReassembler::startAccess(const ControlBits& frame) {
    frames_.clear();
    frames_.push_back(frame);
    phase_ = Phase::Header;
    cts_ = -1;
    header_parsed_ = false;
    header_crc_ok_ = true;
    byte_index_ = 0;
    busy_ = 0;
    command_zero_run_ = 0;
}

void BisscControlReassembler::push(const ControlBits& frame) {
    if (phase_ == Phase::Idle) {
        pushIdle(frame);
        return;
    }

    if (frame.cdm < 0 || frame.cds < 0) {
        // A frame without both control bits breaks the access: the slave's and the
        // master's view of it can no longer be followed. The event spans that frame too.
        frames_.push_back(frame);
        if (phase_ == Phase::Command)
            emitCommand(false, "abandoned");
        else
            emitRegister(false, "abandoned");
        toIdle(0);
        return;
    }
    frames_.push_back(frame);
    const int f = lastIndex();

    switch (phase_) {
        case Phase::Idle:
            break;
        case Phase::Header:
            pushHeader(frame, f);
            break;
        case Phase::WaitSlaveStart:
            if (frame.cds == 1) {
                slave_start_ = f;
                phase_ = Phase::Payload;
            } else if (frame.cdm == 1 && busy_ < kMaxBusyFrames) {
                ++busy_;  // slave busy: the master repeats S
            } else {
                emitRegister(false, "abandoned");
                toIdle(frame.cdm ? 0 : 1);
            }
            break;
        case Phase::Payload:
            if (f == slave_start_ + 13) {
                emitRegister(true, nullptr);
                if (frame.cdm == 1) {  // sequential access: the next byte's S
                    ++byte_index_;
                    s_from_ = f;
                    busy_ = 0;
                    phase_ = Phase::WaitSlaveStart;
                } else {
                    toIdle(2);  // P and this frame's 0
                }
            }
            break;
        case Phase::Command:
            if (frame.cdm == 1) {
                emitCommand(true, nullptr);
                toIdle(0);
            } else if (++command_zero_run_ >= kPreambleZeros) {
                emitCommand(false, "cancelled");
                toIdle(command_zero_run_);
            }
            break;
    }
}

void BisscControlReassembler::pushIdle(const ControlBits& frame) {
    if (frame.cdm < 0) {
        zeros_ = 0;  // a lost frame: the preamble must be seen again
    } else if (frame.cdm == 1 && zeros_ >= kPreambleZeros) {
        startAccess(frame);
    } else {
        zeros_ = frame.cdm ? 0 : zeros_ + 1;
    }
}

void BisscControlReassembler::pushHeader(const ControlBits& frame, int f) {
    if (f == 1) cts_ = frame.cdm;
    if (cts_ == 1 && f == kMasterStartFrame) {
        parseRegisterHeader();
        if (frame.cdm != 1) {  // the master never sent its start bit
            emitRegister(false, "abandoned");
            toIdle(1);
            return;
        }
        phase_ = Phase::WaitSlaveStart;
        s_from_ = f;
        busy_ = 0;
    } else if (cts_ == 0 && f == kCommandStartFrame) {
        if (frame.cdm != 1) {
            emitCommand(false, "abandoned");
            toIdle(1);
            return;
        }
        phase_ = Phase::Command;
        command_zero_run_ = 0;
    }
}

void BisscControlReassembler::parseRegisterHeader() {
    id_ = int(cdmBits(2, 3));
    address_ = int(cdmBits(5, 7));
    const std::uint32_t crc_rx = cdmBits(12, 4);
    // CRC over CTS + ID + ADR, start bit excluded (S2 p.14).
    header_crc_ok_ = bissCrc4(cdmBits(1, 11), 11) == crc_rx;
    rw_ = int(cdmBits(16, 2));
    rw_echo_ = int(cdsBits(17, 2));
    idl_ = int(cdsBits(1, 8));
    header_parsed_ = true;
}

void BisscControlReassembler::emitRegister(bool complete, const char* error) {
    if (frames_.empty()) return;
    Event e;
    e.proto = "bissc";
    e.type = "register";
    const int first = byte_index_ > 0 ? s_from_ : 0;
    e.start = frames_[first].start;
    e.end = frames_.back().end;

    const char* op = "unknown";
    bool crc_ok = header_parsed_ ? header_crc_ok_ : false;
    if (header_parsed_) {
        if (rw_ == 0b10)
            op = "read";
        else if (rw_ == 0b01)
            op = "write";
        else
            e.error("rw");
    }
    e.set("op", std::string(op));
    e.set("id", header_parsed_ ? Value(std::int64_t(id_)) : Value(Null{}));
    e.set("address",
          header_parsed_ ? Value(std::int64_t((address_ + byte_index_) & 0x7F)) : Value(Null{}));
    e.set("data", Null{});  // keeps its place before the optional fields
    if (header_parsed_ && !header_crc_ok_) e.error("control_crc");

    Value data = Null{};
    bool refused = false;
    if (complete) {
        data = checkRegisterPayload(e, crc_ok, refused);
    } else {
        crc_ok = false;
        if (error) e.error(error);
    }
    if (refused) e.error("refused");
    e.set("data", data);
    e.set("crc_ok", crc_ok);
    e.set("refused", refused);
    e.set("busy_frames", std::int64_t(busy_));
    e.set("sequence", std::int64_t(byte_index_));
    if (header_parsed_) e.set("idl", std::int64_t(idl_));
    e.set("frames", std::int64_t(frames_.size() - std::size_t(first)));

    e.summary = registerSummary(op, data, refused, crc_ok);
    emit_(std::move(e));
}

Value BisscControlReassembler::checkRegisterPayload(Event& e, bool& crc_ok, bool& refused) const {
    Value data = Null{};
    const int fs = slave_start_;
    const bool write = rw_ == 0b01;
    if (write) {
        const std::uint32_t d = cdmBits(fs, 8);
        const bool master_crc_ok = bissCrc4(d, 8) == cdmBits(fs + 8, 4);
        const std::uint32_t echo = cdsBits(fs + 1, 8);
        const bool echo_crc_ok = bissCrc4(echo, 8) == cdsBits(fs + 9, 4);
        crc_ok = crc_ok && master_crc_ok && echo_crc_ok;
        if (!master_crc_ok || !echo_crc_ok) e.error("control_crc");
        if (echo != d) e.error("echo");
        if (frames_[fs + 12].cdm != 0) e.error("stop_bit");
        data = std::int64_t(d);
        e.set("echo", std::int64_t(echo));
    } else {
        const std::uint32_t d = cdsBits(fs + 1, 8);
        const bool slave_crc_ok = bissCrc4(d, 8) == cdsBits(fs + 9, 4);
        crc_ok = crc_ok && slave_crc_ok;
        if (!slave_crc_ok) e.error("control_crc");
        data = std::int64_t(d);
    }
    // Refusal: the slave inverts the returned W bit (write -> 00, read -> 11); in a
    // sequential access it returns P = 1 instead (S1 p.13, S2 p.16).
    if (header_parsed_ && (rw_ == 0b10 || rw_ == 0b01)) {
        if (rw_echo_ == (rw_ ^ 0b01))
            refused = true;
        else if (rw_echo_ != rw_)
            e.error("echo");
    }
    if (frames_[fs + 13].cds == 1) {
        if (byte_index_ > 0)
            refused = true;
        else
            e.error("stop_bit");
    }
    return data;
}

std::string BisscControlReassembler::registerSummary(const char* op, const Value& data,
                                                     bool refused, bool crc_ok) const {
    std::string text = fmt::format("{} id={}", op, header_parsed_ ? std::to_string(id_) : "?");
    if (header_parsed_) text += fmt::format(" addr=0x{:02X}", (address_ + byte_index_) & 0x7F);
    if (!isNull(data)) text += fmt::format(" data=0x{:02X}", asInt(data));
    if (refused) text += " refused";
    if (busy_ > 0) text += fmt::format(" busy={}", busy_);
    text += crc_ok ? " crc ok" : " crc bad";
    return text;
}

void BisscControlReassembler::emitCommand(bool executed, const char* error) {
    if (frames_.empty()) return;
    Event e;
    e.proto = "bissc";
    e.type = "command";
    e.start = frames_.front().start;
    e.end = frames_.back().end;
    const bool have_header = lastIndex() >= kCommandStartFrame - 1;
    if (have_header) {
        // IDS0 is sent first; report it as bit 0 so that bit i selects slave i.
        std::int64_t ids = 0;
        std::vector<std::int64_t> targets;
        for (int i = 0; i < 8; ++i) {
            if (frames_[2 + i].cdm) {
                ids |= std::int64_t(1) << i;
                targets.push_back(i);
            }
        }
        const std::uint32_t cmd = cdmBits(10, 2);
        const bool crc_ok = bissCrc4(cdmBits(1, 11), 11) == cdmBits(12, 4);
        e.set("id", ids);
        e.set("command", std::int64_t(cmd));
        e.set("crc_ok", crc_ok);
        e.set("broadcast", ids == 0);
        e.set("targets", targets);
        if (!crc_ok) e.error("control_crc");
        // IDA0..7: the addressed slaves acknowledge on CDS after the second S.
        std::int64_t ida = 0;
        for (int i = 0; i < 8 && kCommandStartFrame + 1 + i <= lastIndex(); ++i)
            if (frames_[kCommandStartFrame + 1 + i].cds) ida |= std::int64_t(1) << i;
        e.set("ida", ida);
        e.summary = fmt::format("command {} ids=0x{:02X}{}{}", cmd, ids,
                                executed ? " executed" : "", crc_ok ? " crc ok" : " crc bad");
    } else {
        e.set("id", Null{});
        e.set("command", Null{});
        e.set("crc_ok", false);
        e.summary = "command (incomplete)";
    }
    e.set("executed", executed);
    if (error) e.error(error);
    emit_(std::move(e));
}

void BisscControlReassembler::finish() {
    if (phase_ == Phase::Idle) return;
    if (phase_ == Phase::Command)
        emitCommand(false, "short_frame");
    else
        emitRegister(false, "short_frame");
    toIdle(0);
}

}  // namespace busdecode
