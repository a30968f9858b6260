#pragma once
// TMC8100 SPI datagram decoder, stacked on the SPI decoder (32-bit words, mode 3 by
// default; SPI options are passed through). Every MOSI word is a `command` event; every
// MISO word that carries data is a `reply` event paired with the command that queued it
// (replies are a FIFO read with later transfers, the last of which may already carry the
// next command); each complete 0x80 read gives an `encoder_read`, which asks the session
// to correlate it with the encoder frame (ssi or bissc) clocked between command and reply.
//
// Errors: unsolicited_reply (data with no command waiting for it), unexpected_reply (not
// the reply the FIFO should hold next), replies_pending (a command sent before the
// previous one's replies were read), avail_low (the first reply read before GPIO6 rose),
// unexpected_avail (an `avail` event: GPIO6 rose with no command waiting), inconsistent
// (binary is not the Gray decode of raw), ssi_mismatch, no_encoder_frame, incomplete,
// crc (BiSS demo: received and calculated CRC differ), short_frame (from the SPI layer).
#include <deque>
#include <map>
#include <optional>

#include "core/block_decoding.h"
#include "core/stacked.h"
#include "tmc8100_datagram.h"

namespace busdecode {

class DecoderFactory;
std::shared_ptr<const DecoderFactory> makeTmc8100Factory();
DecoderInfo tmc8100Info();

enum Tmc8100Role : int { kTmcCs = 0, kTmcSclk, kTmcMosi, kTmcMiso, kTmcAvail, kTmcRoleCount };

class Tmc8100Decoder : public BlockDecoder<Tmc8100Decoder> {
public:
    explicit Tmc8100Decoder(const Options& options);

    void start(const DecoderContext& ctx) override;
    void edge(Tick t, int role, bool level) override;
    void advance(Tick now) override;
    void finish(Tick end) override;
    void glitch(Tick t, int role) override;
    void correlate(Event& e, const EventWindow& window) override;
    bool correlates() const override { return true; }
    Tick watermark(Tick now) const override;

private:
    // A command whose replies are still (partly) in the TMC8100's output FIFO.
    struct Waiting {
        tmc8100::Command cmd;
        Tick start = 0, end = 0;
        std::size_t next = 0;             // index into cmd.replies
        bool only_optional_left = false;  // read_encoder after 0x70, protocol unknown
        Tick avail_rise = kNoTick;        // GPIO6 rose after the command
        Tick first_reply_start = kNoTick, last_reply_end = kNoTick;
        std::optional<std::uint32_t> raw, binary, flags, edges;
        std::vector<std::string> errors;
    };

    void onTransfer(Event&& spi);
    void onMiso(std::uint32_t word, const Event& spi);
    void onMosi(std::uint32_t word, const Event& spi);
    void emitReply(tmc8100::ReplyKind kind, std::uint32_t word, const Event& spi, const Waiting* w,
                   std::vector<std::string> errors);
    void record(Waiting& w, tmc8100::ReplyKind kind, std::uint32_t word);
    void complete(Waiting& w, bool incomplete);
    void finishFront(bool incomplete);
    void updateBusy();
    bool requiredRepliesLeft(const Waiting& w) const {
        return !w.only_optional_left && w.next < w.cmd.replies.size();
    }

    LowerStack stack_;
    std::string mode_option_;
    tmc8100::Firmware firmware_ = tmc8100::Firmware::Unknown;
    tmc8100::EncoderProtocol protocol_ = tmc8100::EncoderProtocol::Unknown;
    bool protocol_fixed_ = false;

    static constexpr std::size_t kMaxWaiting = 4;
    bool miso_bound_ = false;
    bool avail_bound_ = false;
    bool avail_level_ = false;

    std::deque<Waiting> waiting_;
    // Bootloader: the reply to a query is the MISO word of the next transfer.
    std::optional<tmc8100::Command> boot_query_;
    std::optional<int> last_write_address_;
    // Narrow SPI words being assembled into one 32-bit datagram.
    int acc_bits_ = 0;
    std::uint64_t acc_mosi_ = 0, acc_miso_ = 0;
    Tick acc_start_ = 0;
    // encoder_read start -> first reply start: where correlate() looks for the frame.
    std::map<Tick, Tick> corr_window_;
};

}  // namespace busdecode
