// Every input the fuzzers ever crashed on, kept in regressions/<target>/, replayed
// through the same harness code as the fuzzer (fuzz/harness): it must now pass.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

#include "fuzz_harness.h"
#include "support/paths.h"

namespace fs = std::filesystem;

namespace {

struct Case {
    std::string target, path;
};

std::vector<Case> regressionFiles() {
    std::vector<Case> out;
    const fs::path root = ROBUSTNESS_REGRESSIONS_DIR;
    if (!fs::is_directory(root)) return out;
    for (const auto& dir : fs::directory_iterator(root)) {
        if (!dir.is_directory()) continue;
        for (const auto& f : fs::directory_iterator(dir.path()))
            if (f.is_regular_file() && f.path().filename().string().front() != '.')
                out.push_back({dir.path().filename().string(), f.path().string()});
    }
    std::sort(out.begin(), out.end(), [](const Case& a, const Case& b) { return a.path < b.path; });
    return out;
}

class FuzzRegression : public ::testing::TestWithParam<Case> {};

TEST_P(FuzzRegression, ReplaysCleanly) {
    const Case& c = GetParam();
    const auto targets = busdecode::fuzz::targetNames();
    if (std::find(targets.begin(), targets.end(), c.target) == targets.end())
        GTEST_SKIP() << c.target << " is not built in";
    const std::string bytes = busdecode::test::readFile(c.path);
    try {
        busdecode::fuzz::runTarget(c.target, reinterpret_cast<const std::uint8_t*>(bytes.data()),
                                   bytes.size());
    } catch (const busdecode::fuzz::HarnessFailure& e) {
        FAIL() << c.path << ": " << e.what();
    }
}

INSTANTIATE_TEST_SUITE_P(Kept, FuzzRegression, ::testing::ValuesIn(regressionFiles()),
                         [](const ::testing::TestParamInfo<Case>& info) {
                             std::string name = info.param.target + "_" +
                                                fs::path(info.param.path).stem().string();
                             for (auto& ch : name)
                                 if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
                             return name;
                         });
GTEST_ALLOW_UNINSTANTIATED_PARAMETERIZED_TEST(FuzzRegression);

}  // namespace
