#pragma once
// Outputs that would destroy what a run reads or writes: an output file (--report,
// --junit, --save, an LCM log) on one of the run's inputs (a capture, the rules file, the
// capture list), or two outputs on one file. Checked before anything is decoded.
#include <string>
#include <vector>

namespace busdecode {

struct DecodeArgs;

// A file the run reads or writes: what it is ("capture", "--report") and its path.
struct NamedFile {
    std::string what;
    std::string path;
};

// The files a run reads: `captures` (a verify run's list included), the rules file and
// the capture list.
std::vector<NamedFile> runInputs(const DecodeArgs& a, const std::vector<std::string>& captures);

// Throws InputError "OPTION PATH: is the WHAT INPUT, not an output" when `output` is the
// same file as one of `inputs` (a link or another spelling included).
void refuseOutputOnInputs(const std::string& option, const std::string& output,
                          const std::vector<NamedFile>& inputs);

// Throws InputError "OPTION PATH: OTHER writes there too" when two outputs name one file.
// A device or FIFO (written through, never replaced) may take several.
void refuseSharedOutputs(const std::vector<NamedFile>& outputs);

// The log file an LCM URL writes or reads ("file://log.lcm?mode=w" -> "log.lcm"), or ""
// for a provider without one (udpm://, memq://).
std::string lcmLogFile(const std::string& url);

}  // namespace busdecode
