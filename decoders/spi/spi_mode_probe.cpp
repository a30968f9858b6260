#include "spi_mode_probe.h"

#include "spi_info.h"

namespace busdecode {

void SpiModeProbe::start(unsigned levels, bool cs_bound, bool cs_active_high) {
    *this = SpiModeProbe{};
    sclk_ = levels >> kSpiSclk & 1;
    cs_bound_ = cs_bound;
    cs_active_high_ = cs_active_high;
    cs_active_ = !cs_bound || bool(levels >> kSpiCs & 1) == cs_active_high;
}

void SpiModeProbe::attribute(std::uint64_t n, int clock_rose) {
    if (clock_rose == 1) after_rising_ += n;
    if (clock_rose == 0) after_falling_ += n;
}

void SpiModeProbe::edge(Tick t, int role, bool level) {
    ++seen_;
    if (role == kSpiCs) {
        cs_active_ = level == cs_active_high_;
        if (cs_active_) ++(sclk_ ? idle_high_ : idle_low_);
        last_clock_rose_ = -1;  // the first bit's setup follows no clock edge
        pending_ = 0;
    } else if (role == kSpiSclk) {
        sclk_ = level;
        // Data changes at this very tick belong to this edge, whichever came first.
        attribute(pending_, pending_t_ == t ? int(level) : last_clock_rose_);
        pending_ = 0;
        last_clock_rose_ = cs_active_ ? int(level) : -1;
        last_clock_t_ = t;
    } else if ((role == kSpiMosi || role == kSpiMiso) && cs_active_) {
        if (last_clock_t_ == t && last_clock_rose_ >= 0) {
            attribute(1, last_clock_rose_);
        } else {
            if (pending_ && pending_t_ != t) attribute(pending_, last_clock_rose_);
            if (pending_t_ != t) pending_ = 0;
            pending_t_ = t;
            ++pending_;
        }
    }
}

std::optional<SpiModeProbe::Finding> SpiModeProbe::finding() const {
    constexpr std::uint64_t kMinChanges = 16;
    Finding f;
    f.changes = after_rising_ + after_falling_;
    if (f.changes < kMinChanges) return std::nullopt;
    // Data shifted out after the rising edge is sampled on the falling one.
    f.sample_rising = after_falling_ > after_rising_;
    f.agreeing = f.sample_rising ? after_falling_ : after_rising_;
    if (f.agreeing * 10 < f.changes * 9) return std::nullopt;
    if (idle_high_ + idle_low_ > 0 && (idle_high_ == 0 || idle_low_ == 0))
        f.cpol = idle_high_ > 0 ? 1 : 0;
    return f;
}

}  // namespace busdecode
