#pragma once
// Captures with known faults, made by the BiSS-C and SSI generators and written as VCD
// files: one clean capture and one per kind of fault the rules catch, each with the
// time of its first faulty frame (the truth a rule's "first at" must match).
#include <string>
#include <vector>

namespace busdecode::test {

struct FaultCapture {
    std::string path;
    std::string proto;         // "bissc" / "ssi"
    std::string failing_rule;  // "" for a clean capture, else "bissc.max_crc_errors"...
    double first_ns = 0;       // start of the first offending frame
    double second_ns = 0;      // and of the second one, where there is one
};

// Writes the captures into `dir` (once per process) and returns them, BiSS-C first.
const std::vector<FaultCapture>& faultCaptures(const std::string& dir);

// A clean BiSS-C capture whose CDM/CDS carry a sequential register read of 0x7E = 0x69
// and 0x7F = 0x43; `first_ns[i]` is the start of the first frame carrying access i.
struct RegisterCapture {
    std::string path;
    std::vector<double> first_ns;
};
const RegisterCapture& registerCapture(const std::string& dir);

// Rules under which the clean captures pass and each faulty one fails its rule only.
extern const char* const kBisscRules;
extern const char* const kSsiRules;

}  // namespace busdecode::test
