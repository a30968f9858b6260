#pragma once
// Text out of a capture ($date, signal names, file names) is bytes, and JSON and XML must
// be UTF-8: a byte that starts no well-formed sequence is written as U+FFFD.
#include <cstddef>
#include <string>

namespace busdecode {

// The length of the well-formed UTF-8 sequence at s[i] (RFC 3629: shortest form, no
// surrogates, at most U+10FFFF), or 0 where none starts. s[i] >= 0x80.
std::size_t utf8SequenceLength(const std::string& s, std::size_t i);

// Appends the sequence at s[i] (s[i] >= 0x80), or U+FFFD for its first byte where none
// starts; returns how many bytes of `s` it took.
std::size_t appendUtf8OrReplacement(std::string& out, const std::string& s, std::size_t i);

}  // namespace busdecode
