#pragma once
// What the `decode monitor` dashboard knows: per bus (decoder instance) the latest
// position, frame rate, CRC error rate, line delay and register accesses, built from
// the typed LCM messages, and rendered as plain text lines. No terminal or LCM I/O
// here, so tests feed messages and read the text.
#include <cstdint>
#include <deque>
#include <map>
#include <string>
#include <vector>

#include "busdecode_lcm/bissc_command_t.hpp"
#include "busdecode_lcm/bissc_frame_t.hpp"
#include "busdecode_lcm/bissc_register_t.hpp"
#include "busdecode_lcm/decode_status_t.hpp"
#include "busdecode_lcm/event_annotation_t.hpp"
#include "busdecode_lcm/ssi_frame_t.hpp"
#include "busdecode_lcm/tmc8100_encoder_read_t.hpp"
#include "busdecode_lcm/tmcl_reply_t.hpp"
#include "feed_losses.h"

namespace lcm {
class ReceiveBuffer;
}

namespace busdecode {

struct BusView {
    std::string instance, proto;
    std::int64_t events = 0;
    // Position frames (SSI frames, BiSS-C frames, TMC8100 encoder reads).
    std::int64_t frames = 0;
    bool has_position = false;
    std::int64_t position = 0, st = 0, mt = 0;
    // Frames whose check failed: BiSS-C CRC, SSI repeat mismatch, TMC8100 Gray/binary
    // disagreement, TMCL checksum. `checked` counts what could fail.
    std::int64_t checked = 0, check_errors = 0;
    // Frame starts (capture ns) of the last frames, for the rate.
    std::deque<std::int64_t> recent_starts;
    // BiSS-C line delay (ns): last, min, max.
    bool has_line_delay = false;
    double line_delay = 0, line_delay_min = 0, line_delay_max = 0;
    std::int64_t reg_reads = 0, reg_writes = 0, commands = 0;
    std::map<std::string, std::int64_t> errors;  // error string -> count
    std::int64_t last_utime = 0;                 // wall clock of the last message (us)

    // Frames per second of capture time over the recent frames (0 if fewer than 2).
    double frameRateHz() const;
};

class MonitorModel {
public:
    static constexpr std::size_t kRateWindow = 64;
    static constexpr std::size_t kRecentRegisters = 6;

    // LCM handlers (lcm::LCM::subscribe with the generated types).
    void onSsiFrame(const lcm::ReceiveBuffer*, const std::string&,
                    const busdecode_lcm::ssi_frame_t* m);
    void onBisscFrame(const lcm::ReceiveBuffer*, const std::string&,
                      const busdecode_lcm::bissc_frame_t* m);
    void onBisscRegister(const lcm::ReceiveBuffer*, const std::string&,
                         const busdecode_lcm::bissc_register_t* m);
    void onBisscCommand(const lcm::ReceiveBuffer*, const std::string&,
                        const busdecode_lcm::bissc_command_t* m);
    void onEncoderRead(const lcm::ReceiveBuffer*, const std::string&,
                       const busdecode_lcm::tmc8100_encoder_read_t* m);
    void onTmclReply(const lcm::ReceiveBuffer*, const std::string&,
                     const busdecode_lcm::tmcl_reply_t* m);
    void onAnnotation(const lcm::ReceiveBuffer*, const std::string&,
                      const busdecode_lcm::event_annotation_t* m);
    void onStatus(const lcm::ReceiveBuffer*, const std::string&,
                  const busdecode_lcm::decode_status_t* m);

    // The dashboard as lines of at most `width` characters (no terminal codes).
    std::vector<std::string> render(const std::string& url, std::int64_t now_utime,
                                    std::size_t width = 160) const;

    const std::map<std::string, BusView>& buses() const { return buses_; }
    std::int64_t runsEnded() const { return runs_ended_; }
    // Events known lost on the way (FeedLosses).
    std::int64_t lost() const { return losses_.lost(); }
    std::int64_t messages() const { return messages_; }

private:
    BusView& bus(const std::string& instance, std::int64_t utime);
    void frame(BusView& b, std::int64_t start_ns, std::int64_t position, std::int64_t st,
               std::int64_t mt);

    std::map<std::string, BusView> buses_;
    std::deque<std::string> recent_registers_;
    std::string file_, state_ = "waiting";
    std::string liveText() const;

    std::int64_t capture_ns_ = 0, runs_ended_ = 0, messages_ = 0, dropped_ = 0;
    std::int64_t live_samples_ = 0, live_dropped_ = 0;  // decode --device's counts
    FeedLosses losses_;
};

}  // namespace busdecode
