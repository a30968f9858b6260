// `decode --formats` lists every reader: each format name a reader in analyzer/capture can
// report (its formatName() literals, a scope CSV layout's `format = "..."`) is an entry.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <set>

#include "capture/format_list.h"
#include "support/paths.h"

namespace busdecode::test {
namespace {

namespace fs = std::filesystem;

// The quoted words on the lines of `text` that name a format.
std::set<std::string> formatNamesIn(const std::string& text) {
    std::set<std::string> out;
    std::size_t at = 0;
    while (at < text.size()) {
        std::size_t nl = text.find('\n', at);
        if (nl == std::string::npos) nl = text.size();
        const std::string line = text.substr(at, nl - at);
        at = nl + 1;
        const bool names = line.find("formatName() const override") != std::string::npos ||
                           line.find("format = \"") != std::string::npos ||
                           (line.find("return mode_ == 1 ? \"dsview") != std::string::npos);
        for (std::size_t q = line.find('"'); names && q != std::string::npos;) {
            const std::size_t end = line.find('"', q + 1);
            if (end == std::string::npos) break;
            const std::string word = line.substr(q + 1, end - q - 1);
            if (word.size() > 2 &&
                word.find_first_not_of("abcdefghijklmnopqrstuvwxyz0123456789-") ==
                    std::string::npos)
                out.insert(word);
            q = line.find('"', end + 1);
        }
    }
    return out;
}

TEST(FormatList, EveryFormatAReaderReportsIsListed) {
    std::set<std::string> listed;
    for (const auto& f : captureFormats())
        listed.insert(f.name);
    // Not files: the in-memory capture of the tests and Python, libsigrok's devices.
    const std::set<std::string> not_files = {"memory", "sigrok-live", "sigrok-playback"};
    std::size_t seen = 0;
    for (const auto& e : fs::directory_iterator(sourceDir() + "/analyzer/capture")) {
        const std::string file = e.path().filename().string();
        if (e.path().extension() != ".cpp" || file.find("_writer") != std::string::npos) continue;
        for (const std::string& name : formatNamesIn(readFile(e.path().string()))) {
            ++seen;
            if (!not_files.count(name)) {
                EXPECT_TRUE(listed.count(name)) << name << " (" << file << ")";
            }
        }
    }
    EXPECT_GE(seen, 15u) << "the scan found too few format names to be reading the readers";
}

}  // namespace
}  // namespace busdecode::test
