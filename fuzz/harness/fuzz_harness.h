#pragma once
// The fuzz harnesses, shared by the libFuzzer targets (fuzz/) and the regression tests
// (tests/robustness/), so a crashing input kept as a regression file is replayed
// through exactly the code that found it.
//
// Each target takes arbitrary bytes. Inputs the program may reject are rejected the
// documented way (InputError naming the file); anything else that goes wrong is a
// finding: a crash or sanitizer report, a hang (libFuzzer -timeout), unbounded memory
// (-rss_limit_mb), or a broken promise of the interfaces, reported as HarnessFailure.
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/session.h"
#include "core/waveform.h"

namespace busdecode::fuzz {

// A broken contract: out-of-order edges, an exception that is not an InputError, an
// error message without the file name, more events than edges can explain, ...
class HarnessFailure : public std::logic_error {
public:
    using std::logic_error::logic_error;
};

// Target names: "vcd", "vcd_pieces" (vcd_pieces.h), "csv_sigrok", "csv_saleae", "csv_plain", "sr",
// "rules", and one "decoder_<id>" per decoder built in.
std::vector<std::string> targetNames();
// Runs one input through a target; throws HarnessFailure (or crashes) on a finding.
void runTarget(const std::string& target, const std::uint8_t* data, std::size_t size);

// Decodes `w` with one decoder through a real Session and checks what the fuzz
// decoder targets check: no exception out of run(), events in time order and never
// ending before they start, at most 4 events per edge (+64), advice in single lines,
// every field declared by its decoder with a value of its kind (declared_fields.h).
// reads_fields = false: the output reads no fields, as text output (the decoders may
// leave them out), and every event must have a summary or fields. Throws HarnessFailure.
struct DecodeStats {
    bool refused = false;  // the Session refused the options (InputError): not decoded
    std::uint64_t edges = 0, events = 0;
};
DecodeStats decodeChecked(const Waveform& w, const DecoderRequest& req, bool reads_fields = true);

// The inverse of the decoder targets' input format: `w`'s line k drives the decoder's
// role k, with the request's options (seeds for the fuzzers, made from generators).
std::string encodeDecoderInput(const std::string& id, const Waveform& w, const DecoderRequest& req);

// Registers the factories of every decoder built in (idempotent).
void registerDecoders();

}  // namespace busdecode::fuzz
