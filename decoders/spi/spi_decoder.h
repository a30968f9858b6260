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
#include "core/block_decoding.h"
#include "spi_info.h"

namespace busdecode {

class SpiDecoder : public FastDecoder {
public:
    explicit SpiDecoder(const Options& options);

    void start(const DecoderContext& ctx) override;
    void edge(Tick t, int role, bool level) override;
    // Between chip-select changes 64 edges at a time as bit masks (spi_decoder.cpp), the
    // rest through step(); the line state is kept in a local (a member copy would be
    // stored and reloaded around every edge: Edge::t and the state's ticks may alias).
    void edges(const Edge* first, const Edge* last, const int* role_of_line) override;
    void advance(Tick now) override;
    void finish(Tick end) override;
    void glitch(Tick t, int role) override;
    // Most words cut short by chip select, all after the same count: the words are
    // likely that long.
    std::vector<std::string> advice() const override;
    // The word in progress, else the open tick group, holds back the output.
    Tick watermark(Tick now) const override;

private:
    // The four lines, one bit per role (bit(role)): a mask compares and copies them at once.
    struct Lines {
        unsigned level = 0;    // levels including edges of the open tick group
        unsigned settled = 0;  // levels after the last settled group
        Tick tick = 0;         // the open group's tick
        bool open = false;
    };
    // One edge: a later tick first settles the group before it.
    [[gnu::always_inline]] inline void step(Lines& s, Tick t, int role, bool level);
    // Applies every edge seen at s.tick at once (see the header comment).
    [[gnu::always_inline]] inline void settle(Lines& s);
    [[gnu::always_inline]] inline void sampleBit(Tick t, unsigned level);
    // step() for each edge of [first, last).
    void steps(Lines& s, const Edge* first, const Edge* last, const int* role_of_line);
    // edges()'s fast path (spi_decoder.cpp): 64 edges at a time as bit masks.
    struct Window;
    bool classify(const Edge* e, const int* role_of_line, Window& m);
    void run(Lines& s, const Edge* e, const Window& m, int a, int b, const int* role_of_line);
    void sampleRun(const Edge* e, std::uint64_t to, std::uint64_t sclk, std::uint64_t ends, int a,
                   std::uint64_t mosi_at, std::uint64_t miso_at);
    void wordDone(Tick t);
    void emitWord(Tick end, bool short_frame);
    void resetWord();
    static constexpr unsigned bit(int role) { return 1u << role; }
    bool csActive(unsigned levels) const { return bool(levels & bit(kSpiCs)) == cs_active_high_; }

    int cpol_, cpha_, bits_;
    bool lsb_first_, cs_active_high_;
    bool sample_on_rising_;

    unsigned bound_ = 0;  // roles bound to a line, one bit per role
    // The line of each role as edges() has seen it (-1: none yet), for classify().
    int line_of_[kSpiRoleCount] = {-1, -1, -1, -1};
    Lines lines_;

    // The word in progress, in plain integers: edges()'s fast path copies it into a local
    // for its loop, where the compiler keeps it in registers (a member is stored and
    // reloaded on every bit). The bits as BitWord::pushed() pushes them.
    struct Word {
        std::uint64_t mosi = 0, miso = 0;
        int count = 0;
        Tick start = 0;
        Tick last_sample = 0;
        Tick prev_sample = 0;
    };
    // One sampled bit onto `w`: true when the word is complete (wordDone() then follows).
    [[gnu::always_inline]] inline bool takeBit(Word& w, Tick t, unsigned level) const;
    Word word_;
    bool word_glitch_ = false;
    std::int64_t words_ = 0, short_words_ = 0;
    int short_bits_ = -1;  // the bits every short word had (-1: none, or they differ)
};

}  // namespace busdecode
