#pragma once
// Example decoder: reports every pulse on one line with its width. Small on purpose:
// it shows the whole decoder interface (declaration as data, edges in, events out).
#include <core/decoder.h>

namespace pulse {

class PulseDecoder : public busdecode::Decoder {
public:
    explicit PulseDecoder(const busdecode::Options& o);
    void edge(busdecode::Tick t, int role, bool level) override;
    void finish(busdecode::Tick end) override;

private:
    bool active_high_;
    double min_ns_;
    busdecode::Tick since_ = busdecode::kNoTick;
};

const busdecode::DecoderInfo& pulseInfo();

}  // namespace pulse
