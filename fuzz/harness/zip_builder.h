#pragma once
// A minimal ZIP writer (stored entries, no compression) so the .sr fuzz target can turn
// fuzz bytes into a well-formed sigrok session and reach the reader's own logic instead
// of spending its time in libzip's header checks.
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace busdecode::fuzz {

// Entries in order: (name, contents). Returns the archive bytes.
std::string buildStoredZip(const std::vector<std::pair<std::string, std::string>>& entries);

}  // namespace busdecode::fuzz
