#pragma once
// Writes an in-memory Waveform as a scope would have captured it: each line a voltage
// with slow edges, noise, ringing and an offset, in one of the CSV dialects the scope
// reader takes (scope_csv_layout.h); optionally each line as a differential pair of
// wires (NAME+, NAME-), one of which can go open. Generators and tests use it.
#include <cstdint>
#include <string>

#include "core/waveform.h"

namespace busdecode {

enum class ScopeDialect { Rigol, Keysight, Tektronix, Siglent, PicoScope, LeCroy };
inline constexpr ScopeDialect kScopeDialects[] = {ScopeDialect::Rigol,     ScopeDialect::Keysight,
                                                  ScopeDialect::Tektronix, ScopeDialect::Siglent,
                                                  ScopeDialect::PicoScope, ScopeDialect::LeCroy};
const char* scopeDialectName(ScopeDialect d);

struct AnalogStyle {
    double sample_ns = 20;
    double low_v = 0, high_v = 3.3;
    double offset_v = 0;  // added to every wire
    double rise_ns = 0;   // the 0-100 % ramp, centred on the edge (10-90 % is 0.8 of it)
    double snr_db = 0;    // > 0: Gaussian noise, 20 log10((swing / 2) / sigma)
    double ringing = 0;   // overshoot after an edge, as a fraction of the swing
    double ring_ns = 50;  // its period (and its decay time)
    bool differential = false;
    // With differential: from this time on, the negative wire of this line is open
    // (sits at the middle of the swing).
    int open_line = -1;
    double open_after_ns = 0;
    std::uint64_t seed = 1;
};

void writeScopeCsv(const Waveform& w, const std::string& path, ScopeDialect dialect,
                   const AnalogStyle& style);

}  // namespace busdecode
