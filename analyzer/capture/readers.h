#pragma once
// The concrete readers behind openCapture(); each takes an input that openCapture has
// already recognised by its content.
#include <memory>
#include <string>
#include <string_view>

#include "capture_reader.h"
#include "text_source.h"

namespace busdecode {

std::unique_ptr<CaptureReader> openVcd(std::unique_ptr<TextSource> src, const OpenOptions& opts);
std::unique_ptr<CaptureReader> openCsv(std::unique_ptr<TextSource> src, const OpenOptions& opts);
// Opens `path`, or when fd >= 0 that descriptor (a seekable copy of standard input,
// owned by the reader); `name` is what messages call the file.
std::unique_ptr<CaptureReader> openSr(const std::string& path, int fd, const std::string& name,
                                      const OpenOptions& opts);

// Text for a message: bytes that are not printable ASCII shown as \xNN, cut at `max`.
std::string printable(std::string_view s, std::size_t max = 40);

}  // namespace busdecode
