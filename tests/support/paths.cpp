#include "paths.h"

#include <sys/wait.h>
#include <unistd.h>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "core/scratch_dir.h"

namespace busdecode::test {

std::string sourceDir() {
    if (const char* e = std::getenv("BUSDECODE_SOURCE_DIR")) return e;
    return BUSDECODE_SOURCE_DIR;
}

std::string realCaptures() {
    return sourceDir() + "/tests/data/real";
}

std::string binDir() {
    if (const char* e = std::getenv("BUSDECODE_BIN_DIR")) return e;
    return BUSDECODE_BIN_DIR;
}

std::string tempDir() {
    // The test process's scratch directory, removed when the process exits
    // (BUSDECODE_KEEP_TEST_FILES=1 keeps it, to look at a failing test's files): ctest runs
    // every test in a process of its own, and /tmp would otherwise collect thousands.
    static const ScratchDir dir("busdecode-test",
                                std::getenv("BUSDECODE_KEEP_TEST_FILES") != nullptr);
    return dir.path();
}

std::string readFile(const std::string& path) {
    std::ifstream f(path, std::ios::binary);
    if (!f) throw std::runtime_error("cannot read " + path);
    std::ostringstream ss;
    ss << f.rdbuf();
    return ss.str();
}

void writeFile(const std::string& path, const std::string& text) {
    std::ofstream f(path, std::ios::binary);
    f << text;
}

std::string shellQuote(const std::string& s) {
    std::string out = "'";
    for (char c : s) {
        if (c == '\'')
            out += "'\\''";
        else
            out += c;
    }
    return out + "'";
}

RunResult runCommand(const std::string& cmdline) {
    const std::string dir = tempDir();
    static int counter = 0;
    const std::string outf = dir + "/run" + std::to_string(++counter) + ".out";
    const std::string errf = dir + "/run" + std::to_string(counter) + ".err";
    const std::string full =
        "( " + cmdline + " ) >" + shellQuote(outf) + " 2>" + shellQuote(errf) + " </dev/null";
    int st = std::system(full.c_str());
    RunResult r;
    r.status = (st != -1 && WIFEXITED(st)) ? WEXITSTATUS(st) : -1;
    r.out = readFile(outf);
    r.err = readFile(errf);
    return r;
}

std::vector<std::string> splitLines(const std::string& text) {
    std::vector<std::string> out;
    std::istringstream in(text);
    for (std::string l; std::getline(in, l);)
        out.push_back(l);
    return out;
}

RunResult runDecode(const std::vector<std::string>& args) {
    std::string cmd = shellQuote(binDir() + "/decode");
    for (const auto& a : args)
        cmd += " " + shellQuote(a);
    return runCommand(cmd);
}

}  // namespace busdecode::test
