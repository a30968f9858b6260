#pragma once
// The SPI decoder's declaration as data: roles, options and events. Kept apart from the
// state machine because decoders stacked on SPI (TMC8100) declare the same roles and
// options again, with the same names and defaults, so they can be passed through.
#include <memory>
#include <vector>

#include "core/decoder_info.h"

namespace busdecode {

class DecoderFactory;

// Role indices, in DecoderInfo::roles order.
enum SpiRole : int { kSpiCs = 0, kSpiSclk = 1, kSpiMosi = 2, kSpiMiso = 3, kSpiRoleCount = 4 };

std::vector<RoleSpec> spiRoleSpecs();
// cpol, cpha, bits, lsb_first, cs_polarity with the contract defaults.
std::vector<OptionSpec> spiOptionSpecs();
DecoderInfo spiInfo();

std::shared_ptr<const DecoderFactory> makeSpiFactory();

}  // namespace busdecode
