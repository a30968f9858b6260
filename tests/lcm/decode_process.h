#pragma once
// Runs build/bin/decode as a child with its standard input and output on pipes, so a
// test can feed a capture piece by piece and read events as they come. No gtest
// assertions inside: usable from forked test helpers too.
#include <sys/types.h>

#include <string>
#include <vector>

namespace busdecode::test {

struct DecodeProcess {
    pid_t pid = -1;
    int in = -1;   // write end of decode's standard input
    int out = -1;  // read end of decode's standard output
};

// pid -1 when it could not start.
DecodeProcess spawnDecode(const std::vector<std::string>& args);
// Writes all of `s` (false on a write error).
bool writeAll(int fd, const std::string& s);

}  // namespace busdecode::test
