#pragma once
// Internal to the harness: the reader targets.
#include <cstddef>
#include <cstdint>
#include <string>

namespace busdecode::fuzz {

enum class ReaderKind {
    Text,      // VCD, sigrok and Saleae CSV: the bytes are the file
    PlainCsv,  // the same with --rate (plain CSV has no time column)
    Sr,        // structured bytes packed into a sigrok session ZIP
    Dsl,       // structured bytes packed into a DSView session ZIP
};
void runReaderTarget(ReaderKind kind, const std::uint8_t* data, std::size_t size);
std::string srFromFuzzBytes(const std::uint8_t* data, std::size_t size);
std::string dslFromFuzzBytes(const std::uint8_t* data, std::size_t size);

// Decoder targets: `id` is the decoder id.
void runDecoderTarget(const std::string& id, const std::uint8_t* data, std::size_t size);
// The rules-file parser (only when analyzer/verify is built in).
void runRulesTarget(const std::uint8_t* data, std::size_t size);
// The command line's numbers and options (cli_args_harness.cpp).
void runCliArgsTarget(const std::uint8_t* data, std::size_t size);

}  // namespace busdecode::fuzz
