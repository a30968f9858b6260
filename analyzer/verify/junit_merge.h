#pragma once
// `decode merge-junit SHARD.xml... -o ALL.xml [--from-list FILE]`: joins the JUnit files
// of `decode verify --shard K/N` runs into one whose testcases, counts and summary equal
// a single run over the whole list. A shard with no usable file (never written, killed,
// cut short) becomes one <error> testcase per capture it should have checked (one for the
// whole shard when the list is not given); the merge then exits 2.
#include <string>
#include <vector>

#include "verdict.h"

namespace busdecode {

// What one shard's file holds (the parts a merge keeps).
struct JunitShardFile {
    std::string path;
    std::string rules, shard, checks;  // the <property> values ("" if absent)
    std::vector<JunitCase> cases;
    std::string out, err;  // <system-out>, <system-err>
};

// Throws InputError naming the file (and line) when it is not a verify JUnit file.
JunitShardFile readJunitShard(const std::string& path);

struct MergeResult {
    std::string xml;
    std::string summary;                // as `decode verify` prints it
    std::vector<std::string> problems;  // one line per missing or unusable shard
    bool any_error = false, any_failure = false;
};

// A file given that readJunitShard() refused, and its message.
struct UnusableJunitFile {
    std::string path, why;
};

// `files` are the readable ones: a shard among 1..N without one is missing. `expected`
// is the whole capture list when `list_given` (--from-list). Of merges of whole runs
// without the list, each `unusable` file becomes an <error> testcase of its own: whose
// captures it held is unknown, and a merge of nothing usable is never a pass.
MergeResult mergeJunit(const std::vector<JunitShardFile>& files,
                       const std::vector<std::string>& expected, bool list_given,
                       const std::vector<UnusableJunitFile>& unusable = {});

// The command: exit 0 all pass, 1 any rule failed, 2 any error or missing shard.
int runMergeJunit(int argc, char** argv);

}  // namespace busdecode
