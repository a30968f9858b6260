#pragma once
// SIGINT and SIGTERM set a flag that the readers and the decode loop poll, so a run ends
// at its next block or poll with an honest status instead of dying mid-write. The
// handlers are installed without SA_RESTART: a blocking call (a wait on a FIFO or a
// slow device) returns EINTR and its caller looks at the flag.
#include <atomic>
#include <string>

namespace busdecode {

// Installs the handlers (also over an inherited SIG_IGN: a background job asked to stop
// with kill -INT stops too).
void catchInterruptions();
const std::atomic<bool>* interruptionFlag();
bool interrupted();
// The exit status of an interrupted run: 128 + the signal (130 SIGINT, 143 SIGTERM).
int interruptedStatus();
std::string interruptingSignalName();  // "SIGINT" or "SIGTERM"

}  // namespace busdecode
