#pragma once
// Where tests find things: the source tree, the real captures committed in it
// (tests/data/real, sources and licences in its README), and the built CLI.
#include <string>
#include <vector>

namespace busdecode::test {

std::string sourceDir();
std::string realCaptures();  // tests/data/real
std::string binDir();        // build/bin (decode, plugins/)
std::string tempDir();       // a fresh directory for this test process
std::string readFile(const std::string& path);
void writeFile(const std::string& path, const std::string& text);
// The lines of a text (a CLI's output), without their newlines.
std::vector<std::string> splitLines(const std::string& text);

struct RunResult {
    int status = -1;  // exit status, or -1 if it did not exit normally
    std::string out, err;
};
// Runs a shell command line (sh -c), capturing stdout and stderr.
RunResult runCommand(const std::string& cmdline);
// Runs build/bin/decode with the arguments (each shell-quoted).
RunResult runDecode(const std::vector<std::string>& args);
std::string shellQuote(const std::string& s);

}  // namespace busdecode::test
