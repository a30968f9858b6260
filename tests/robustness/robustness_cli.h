#pragma once
// The CLI's answer to one bad input: exit status 2 and one line on stderr.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "support/paths.h"

namespace busdecode::test {

// Runs decode with `args`; expects exit 2 and a single stderr line, which it returns
// without its newline.
inline std::string oneLineFailure(const std::vector<std::string>& args) {
    const RunResult r = runDecode(args);
    EXPECT_EQ(r.status, 2) << "stdout: " << r.out.substr(0, 300) << "\nstderr: " << r.err;
    std::string err = r.err;
    if (!err.empty() && err.back() == '\n') err.pop_back();
    EXPECT_FALSE(err.empty());
    EXPECT_EQ(err.find('\n'), std::string::npos) << "more than one line: " << err;
    return err;
}

inline std::string caseFile(const std::string& name, const std::string& text) {
    const std::string path = tempDir() + "/" + name;
    writeFile(path, text);
    return path;
}

}  // namespace busdecode::test
