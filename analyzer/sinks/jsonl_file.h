#pragma once
// What `decode FILE --proto X --format jsonl` prints, as a string: the golden outputs
// beside the example captures are made and checked with this.
#include <map>
#include <string>

namespace busdecode {

std::string decodeFileToJsonl(const std::string& path, const std::string& proto,
                              const std::map<std::string, std::string>& options);

// "dir/ssi_x.vcd" -> "dir/ssi_x.golden.jsonl"
std::string goldenPathFor(const std::string& capture);

}  // namespace busdecode
