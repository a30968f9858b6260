#pragma once
// Generic asynchronous serial (UART) decoder: one or two lines (rx, tx), each sampled
// mid-bit from its start edge (the sigrok convention, so sample indices match its
// expected outputs). Emits `uart`/`byte` events with `value` and `line`; framing and
// parity faults are errors; a line held low for a whole frame is a `break` event.
//
// Event payload for stacked decoders (TMCL): type "byte", fields value (int), line
// ("rx"/"tx"), start/end = start edge to the end of the stop bits.
#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "baud_estimator.h"
#include "core/block_decoding.h"
#include "core/line_sampler.h"
#include "uart_format.h"

namespace busdecode {

class DecoderFactory;

class UartDecoder : public BlockDecoder<UartDecoder> {
public:
    explicit UartDecoder(const Options& options);

    void start(const DecoderContext& ctx) override;
    void edge(Tick t, int role, bool level) override;
    void advance(Tick now) override;
    void finish(Tick end) override;
    // Most characters with framing or parity errors: the rate, the format or the
    // polarity is the likely cause.
    std::vector<std::string> advice() const override;

    // Ticks per bit once the rate is known (0 while baud=auto is still measuring).
    double bitTicks() const { return bit_ticks_; }

private:
    struct Line {
        std::string name;
        bool bound = false;
        bool level = true;  // raw line level
        LineSampler sampler;
        std::uint32_t generation = 0;  // samples of an abandoned frame carry an old one
        bool in_frame = false;
        Tick frame_start = 0;
        std::uint32_t value = 0;
        bool parity_bit = false;
        bool stop_ok = true;
        bool all_low = true;
        bool in_break = false;
        Tick break_start = 0;
    };
    struct HeldEdge {
        Tick t;
        int role;
        bool level;
    };

    void decodeEdge(Tick t, int role, bool level);
    void settleOtherLines(Tick t, int except);
    void drain(Line& line);
    void onSample(Line& line, const LineSampler::Sample& s);
    void startFrame(Line& line, Tick t);
    void endFrame(Line& line, bool cut_short);
    void emitBreak(Line& line, Tick end);
    double samplePoint(Tick frame_start, int slot) const;
    Tick frameEnd(Tick frame_start) const;
    void decideBaud();
    // A given baud rate the measured pulses disagree with: the rate they fit.
    std::optional<std::string> baudHint() const;
    void updateBusy();

    UartFormat fmt_;
    bool auto_baud_ = false;
    double bit_ticks_ = 0;
    std::array<Line, 2> lines_;
    // baud=auto: edges are held until enough pulses are seen, then replayed.
    std::vector<HeldEdge> held_;
    BaudEstimator estimator_{2, true};
    std::size_t checked_edges_ = 0;               // edges measured with a given baud (advice())
    std::uint64_t bytes_ = 0, faulty_bytes_ = 0;  // characters decoded; with framing/parity errors
};

std::shared_ptr<const DecoderFactory> makeUartFactory();

}  // namespace busdecode
