#include "core/options.h"
#include "readers.h"

namespace busdecode {
std::unique_ptr<CaptureReader> openCsv(std::unique_ptr<TextSource> src, const OpenOptions&) {
    throw InputError(src->name() + ": CSV not supported yet");
}
}  // namespace busdecode
