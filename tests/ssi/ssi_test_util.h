#pragma once
// Shared helpers of the SSI tests: run the decoder over a generated capture and compare
// each frame with the generator's truth.
#include <map>
#include <string>
#include <vector>

#include "core/event.h"
#include "ssi_generator.h"

namespace busdecode::ssitest {

// Decodes with `--proto ssi` and the given options; returns the `frame` events.
std::vector<Event> decodeFrames(const Waveform& w, std::map<std::string, std::string> opts);

// Registers the ssi factory once.
void registerSsi();

std::uint64_t u64(const Event& e, const char* key);
std::int64_t i64(const Event& e, const char* key);
bool flag(const Event& e, const char* key);
std::string describe(const Event& e);

// Every frame equals its truth: times, raw, bits, repeats, match, tm (within a tick),
// and no errors besides `allowed`.
void expectTruth(const std::vector<Event>& frames, const SsiGenerated& g,
                 const std::vector<std::string>& allowed = {});

}  // namespace busdecode::ssitest
