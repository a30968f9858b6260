// The SSI decoder's entry in the registry (built-in plugin and tests).
#include <memory>

#include "ssi_factory.h"

#include "core/registry.h"
#include "ssi_config.h"
#include "ssi_decoder.h"

namespace busdecode {

std::shared_ptr<const DecoderFactory> makeSsiFactory() {
    return std::make_shared<SimpleFactory<SsiDecoder>>(ssiInfo());
}

}  // namespace busdecode
