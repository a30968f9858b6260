#pragma once
// The concrete readers behind openCapture(); each takes an input that openCapture has
// already recognised by its content.
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "capture_reader.h"
#include "text_source.h"

namespace busdecode {

std::unique_ptr<CaptureReader> openVcd(std::unique_ptr<TextSource> src, const OpenOptions& opts);
std::unique_ptr<CaptureReader> openCsv(std::unique_ptr<TextSource> src, const OpenOptions& opts);
// A scope's CSV (scope_csv_layout.h), taking `src`; null, leaving `src`, for other CSVs.
std::unique_ptr<CaptureReader> openScopeCsvIfScope(std::unique_ptr<TextSource>& src,
                                                   const OpenOptions& opts);
class ZipArchive;
// ZIP captures, the archive already open (zip_archive.h).
std::unique_ptr<CaptureReader> openSr(std::unique_ptr<ZipArchive> archive, const OpenOptions& opts);
std::unique_ptr<CaptureReader> openDsl(std::unique_ptr<ZipArchive> archive,
                                       const OpenOptions& opts);

// Saleae Logic 2 binary export: one digital_N.bin or analog_N.bin, or a folder of them
// (its digital files, or without any its analog ones).
std::unique_ptr<CaptureReader> openSaleaeBin(const std::string& path, const OpenOptions& opts);
// Analog channels (saleae_analog_samples.cpp): (path, channel name) each, one capture.
std::unique_ptr<CaptureReader> openSaleaeAnalog(
    const std::string& name, const std::vector<std::pair<std::string, std::string>>& files,
    const OpenOptions& opts);

// An FST file (fst_reader.cpp) at `path`, named `name` in messages; `owned_fd` (or -1), a
// descriptor behind `path` that the reader closes when done.
std::unique_ptr<CaptureReader> openFst(const std::string& path, const std::string& name,
                                       const OpenOptions& opts, int owned_fd = -1);

// A sigrok session of analog channels only (sr_analog_samples.cpp); null for others.
std::unique_ptr<CaptureReader> openSrAnalogIfAnalog(const std::string& path,
                                                    const std::string& name,
                                                    const OpenOptions& opts);

// "24 MHz", "1MHz", "5 Hz", "100 kHz", "24000000" -> Hz (0 if it is not a rate).
std::int64_t parseRateHz(std::string_view text);

// Text for a message: bytes that are not printable ASCII shown as \xNN, cut at `max`.
std::string printable(std::string_view s, std::size_t max = 40);

}  // namespace busdecode
