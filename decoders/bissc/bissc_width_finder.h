#pragma once
// `--opt bits=auto`: the position width found from the traffic, for an encoder whose data
// length is not known (a RESOLUTE sends 32 bits, a 36-bit one 36; the default is 26).
//
// The first edges are held back (at most kLearnEdges of them or kLearnSeconds of capture,
// fewer when one width soon stands out: kTryEvery, kSureFrames); each width from 1 to 64
// decodes them, and the width under which the most frames are clean wins: CRC right, a
// low stop bit, no fault but nE/nW (which the encoder reports whatever the width). A wrong
// width passes a 6-bit CRC and the stop bit by chance once in 128 frames (a longer one,
// whose stop bit falls in the timeout, once in 64), so with a few frames the true width
// stands alone. Ties (one frame, or a standing encoder whose frames repeat) go to the
// larger width: every width below the true one may pass by chance, above it only the few
// the master clocks past the stop bit.
// Then a BisscDecoder of that width decodes the held edges and everything after them, so
// the events are those of `--opt bits=N`. Without a clean frame, the default 26 is used.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/block_decoding.h"
#include "core/options.h"

namespace busdecode {

class BisscDecoder;

class BisscWidthFinder : public FastDecoder {
public:
    static constexpr std::size_t kLearnEdges = 20000;  // about 200 frames of 26 bits
    static constexpr double kLearnSeconds = 0.5;       // bounds --follow's wait
    // Every kTryEvery held edges the widths are tried; kSureFrames clean frames under
    // one width, and under no other a quarter as many, decide at once (a standing
    // encoder, whose frames repeat, waits for the full span: a wrong width may fit them
    // all).
    static constexpr std::size_t kTryEvery = 2000;
    static constexpr std::uint64_t kSureFrames = 8;

    // `options` with bits=auto; the other options as given (checked here, for width 64).
    explicit BisscWidthFinder(const Options& options);
    ~BisscWidthFinder() override;

    void start(const DecoderContext& ctx) override;
    void edge(Tick t, int role, bool level) override;
    void edges(const Edge* first, const Edge* last, const int* role_of_line) override;
    void advance(Tick now) override;
    void finish(Tick end) override;
    void glitch(Tick t, int role) override;
    Tick watermark(Tick now) const override;
    // The chosen decoder's, or (no width fitted) advice to check the lines and the CRC.
    std::vector<std::string> advice() const override;

    // The width chosen (0 while still learning).
    int width() const { return width_; }

private:
    struct Held {
        Tick t;
        int role;
        bool level;
        bool glitch;  // a removed pulse (Decoder::glitch), not an edge
    };
    struct Scores {
        int best = 0;  // the width with the most clean frames (0: none has any)
        std::uint64_t best_clean = 0, runner_up_clean = 0;
    };
    void hold(const Held& h);
    // Every width's clean frames among the held edges. At the end of the capture (`end`
    // set) the candidates see it too, so that the last frames count.
    Scores score(Tick end) const;
    // Starts the real decoder with width `best` (0: none fits, the default) and hands it
    // the held edges.
    void decide(int best);
    // kLearnSeconds of capture have passed since the first held edge.
    bool spanOver(Tick now) const;
    static void replay(Decoder& d, const std::vector<Held>& held);
    std::unique_ptr<BisscDecoder> makeDecoder(int bits) const;  // nullptr: options don't fit

    Options options_;
    std::vector<Held> held_;
    Tick last_advance_ = kNoTick;
    std::unique_ptr<BisscDecoder> decoder_;  // once the width is known
    int width_ = 0;
    bool found_ = false;  // width_ fitted the traffic (not the default for want of one)
};

}  // namespace busdecode
