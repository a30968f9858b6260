#pragma once
// `decode --device` and `--scan` run in a module of their own (busdecode_live.so, beside
// the core library), loaded only when asked for: libsigrok and the sixteen libraries it
// pulls in would otherwise load with every decode (2.4 MB and 3 ms at each start).
#include <atomic>
#include <string>
#include <vector>

#include "capture/live_device.h"
#include "core/session.h"

namespace busdecode {

// What the module hands out; built together with decode, checked by `abi`.
struct LiveModule {
    int abi;
    CaptureFacts (*decode)(const LiveSettings& settings,
                           const std::vector<DecoderRequest>& requests,
                           const std::vector<OutputSink*>& sinks, const std::atomic<bool>* stop);
    std::vector<std::string> (*scan)();
};

constexpr int kLiveModuleAbi = 1;
// The C name the module exports: a function returning its LiveModule.
#define BUSDECODE_LIVE_ENTRY busdecode_live_module

// Loads the module once; throws InputError naming the option and where it looked.
const LiveModule& liveModule(const std::string& option);

}  // namespace busdecode
