#pragma once
// TMCL datagram decoder, stacked on the UART decoder (LowerStack). Lines: `host` (host
// to module) and `module` (module to host), or `bus`, one half-duplex RS-485 line that
// carries both directions: there a datagram is a reply when it follows a command and
// answers it (same command number) or has a reply's shape (status code + command).
// When `bus` is bound, `host` and `module` are ignored.
// Bytes are grouped by 9; a pause longer than `gap_bytes` character times inside a
// datagram resynchronises and reports the cut datagram (`short_frame`). Each reply is
// paired with the command before it: `rtt_ns` (command start to reply end) and
// `latency_ns` (command end to reply start).
#include <array>
#include <memory>
#include <vector>

#include "core/block_decoding.h"
#include "core/stacked.h"
#include "tmcl_datagram.h"

namespace busdecode {

class DecoderFactory;

class TmclDecoder : public BlockDecoder<TmclDecoder> {
public:
    explicit TmclDecoder(const Options& options);
    ~TmclDecoder() override;

    void start(const DecoderContext& ctx) override;
    void edge(Tick t, int role, bool level) override;
    void advance(Tick now) override;
    void finish(Tick end) override;
    void glitch(Tick t, int role) override;
    Tick watermark(Tick now) const override;
    // The UART's advice: a wrong rate or format garbles every datagram.
    std::vector<std::string> advice() const override;

private:
    enum Stream { kHost = 0, kModule = 1, kBus = 2 };
    struct ByteIn {
        std::uint8_t value;
        Tick start, end;
        bool fault;  // UART framing or parity error
    };
    struct PendingCommand {
        tmcl::Command command;
        std::string text;
        Tick start = 0, end = 0;
        bool awaiting = false;
    };

    void onUartEvent(Stream stream, Event&& e);
    void onByte(Stream stream, const ByteIn& b);
    void flushShort(Stream stream);
    void checkGaps(Tick now);
    void onDatagram(Stream stream, const std::vector<ByteIn>& bytes);
    void emitCommand(const tmcl::Datagram& d, Tick start, Tick end, bool fault);
    void emitReply(const tmcl::Datagram& d, Tick start, Tick end, bool fault);
    void emitVersionReply(const tmcl::Datagram& d, Tick start, Tick end, bool fault);
    void pairWithCommand(Event& e, Tick start, Tick end);
    bool isReplyOnBus(const tmcl::Datagram& d) const;
    Tick lowerWatermark(Tick now) const;
    void updateBusy();

    Options options_;
    double gap_bytes_ = 3;
    int host_address_ = -1, module_address_ = -1;  // -1: any
    std::unique_ptr<LowerStack> lines_, bus_;
    std::array<std::vector<ByteIn>, 3> partial_;
    PendingCommand pending_;
};

std::shared_ptr<const DecoderFactory> makeTmclFactory();

}  // namespace busdecode
