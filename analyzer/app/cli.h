#pragma once
namespace busdecode {
// The `decode` command line (see README and ../shared/CONTRACT.md). Returns the exit status.
int runCli(int argc, char** argv);
}  // namespace busdecode
