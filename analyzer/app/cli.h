#pragma once
namespace busdecode {
// The `decode` command line (see README and docs/contract.md). Returns the exit status.
int runCli(int argc, char** argv);
}  // namespace busdecode
