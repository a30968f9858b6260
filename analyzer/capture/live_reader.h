#pragma once
// `decode --device ...`: a live acquisition as a CaptureReader. The device's samples
// become edges on the acquisition thread (LiveEdgeMaker) and wait in a bounded queue
// (LiveEdgeQueue) for next(), so the session, decoders and sinks run as for a file.
#include <atomic>
#include <memory>
#include <string>
#include <vector>

#include "capture_reader.h"
#include "core/session.h"
#include "live_device.h"

namespace busdecode {

class LiveReader;

// Opens the device (InputError on a bad one) and decodes until its end, the limit or
// *stop (Ctrl-C), which ends it as a normal end. A device gone mid-run, or a --save that
// cannot be written, throws InputError after the sinks have ended (summary and report
// kept).
CaptureFacts decodeLive(const LiveSettings& settings, const std::vector<DecoderRequest>& requests,
                        const std::vector<OutputSink*>& sinks, const std::atomic<bool>* stop);

std::unique_ptr<LiveReader> openLive(const LiveSettings& settings, const std::atomic<bool>* stop);

}  // namespace busdecode
