#pragma once
// The standard streams of a run: made safe before anything opens a descriptor, written
// without ever throwing, and checked at the end, so a closed or full stdout or stderr
// gives exit status 2, never an abort and never a silent success.
#include <string_view>

namespace busdecode {

struct StandardStreams {
    bool stdin_closed = false;
    bool stdout_closed = false;
};

// Puts a placeholder on each of descriptors 0, 1 and 2 that is closed, so that no
// descriptor opened later (Qt's eventfd, a capture, a report) takes its number: /dev/null
// opened for the other direction, so reading a closed stdin or writing a closed stdout
// still fails (EBADF). Call first, before Qt or anything else opens a descriptor.
StandardStreams guardStandardStreams();
const StandardStreams& standardStreams();

// Writes `text` to stderr and flushes; never throws (a failed write is remembered).
void printError(std::string_view text);
// True once a write to stderr failed (the run then ends with status 2).
bool standardErrorFailed();

// Flushes stdout. Throws InputError "standard output: cannot write: WHY" when this or an
// earlier write to it failed.
void checkStandardOutput();

}  // namespace busdecode
