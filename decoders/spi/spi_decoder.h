#pragma once
// Generic SPI decoder. Emits one `spi`/`transfer` event per word.
//
// Sampling follows sigrok's SPI decoder so sample indices compare 1:1 with its expected
// outputs: a bit is taken at every sampling clock edge (rising for modes 0 and 3,
// falling for modes 1 and 2) while cs is asserted; data lines are read *after* every
// change at that same tick (a sample-based analyser sees the new level there). A word
// starts at its first sampling edge and ends one bit period after its last one.
// A cs change resets the word: a partial word is reported with the error short_frame
// (sigrok drops it silently). Without cs, words are framed by bit count only.
//
// Event payload for stacked decoders (TMC8100): type "transfer", fields mosi, miso
// (uint64, bits wide, or Null for an unbound line), bits (int); errors short_frame,
// glitch.

#include "core/bit_word.h"
#include "core/decoder.h"
#include "spi_info.h"

namespace busdecode {

class SpiDecoder : public BlockDecoder<SpiDecoder> {
public:
    explicit SpiDecoder(const Options& options);

    void start(const DecoderContext& ctx) override;
    void edge(Tick t, int role, bool level) override;
    void advance(Tick now) override;
    void finish(Tick end) override;
    void glitch(Tick t, int role) override;

private:
    // Applies every edge seen at group_tick_ at once (see the header comment).
    [[gnu::always_inline]] inline void settle();
    void sampleBit(Tick t);
    void emitWord(Tick end, bool short_frame);
    void resetWord();
    static constexpr unsigned bit(int role) { return 1u << role; }
    bool csActive(unsigned levels) const { return bool(levels & bit(kSpiCs)) == cs_active_high_; }

    int cpol_, cpha_, bits_;
    bool lsb_first_, cs_active_high_;
    bool sample_on_rising_;

    // One bit per role (bit(role)): a mask compares and copies the four lines at once.
    unsigned bound_ = 0;    // roles bound to a line
    unsigned level_ = 0;    // levels including edges of the open tick group
    unsigned settled_ = 0;  // levels after the last settled group
    bool group_open_ = false;
    Tick group_tick_ = 0;

    BitWord mosi_, miso_;
    int count_ = 0;
    Tick word_start_ = 0;
    Tick last_sample_ = 0;
    Tick prev_sample_ = 0;
    bool word_glitch_ = false;
};

}  // namespace busdecode
