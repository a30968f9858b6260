// The entry point of busdecode_live.so (app/live_module.h): acquisition through libsigrok.
#include "app/live_module.h"
#include "live_reader.h"
#include "live_sigrok.h"

extern "C" __attribute__((visibility("default"))) const busdecode::LiveModule*
BUSDECODE_LIVE_ENTRY() {
    static const busdecode::LiveModule module{busdecode::kLiveModuleAbi, &busdecode::decodeLive,
                                              &busdecode::scanSigrokDevices};
    return &module;
}
