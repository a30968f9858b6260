// Writes the decoders' example captures into CAPTURE_DIR exactly as they are committed:
//   make_examples CAPTURE_DIR [ID...]      (no ID: every decoder built)
// Each decoder lists its examples itself (listExamples in <id>_examples.cpp). Their
// golden outputs come from one place: tests/golden/golden.py --write BIN_DIR.
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "example.h"

using namespace busdecode;

namespace {

std::string knownIds() {
    std::string ids;
    for (const auto& [id, list] : listedExamples())
        ids += (ids.empty() ? "" : ", ") + id;
    return ids;
}

void writeAll(const ExampleList& list, const std::string& dir) {
    for (const auto& ex : list()) {
        writeExample(ex, dir + "/" + ex.file);
        std::printf("%s/%s: %s\n  %s\n", dir.c_str(), ex.file.c_str(), ex.description.c_str(),
                    decodeCommand("captures/" + ex.file, ex.requests).c_str());
    }
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: make_examples CAPTURE_DIR [ID...] (ids: %s)\n",
                     knownIds().c_str());
        return 2;
    }
    std::vector<const ExampleList*> chosen;
    for (int i = 2; i < argc; ++i) {
        const auto it = listedExamples().find(argv[i]);
        if (it == listedExamples().end()) {
            std::fprintf(stderr, "make_examples: no decoder '%s' (ids: %s)\n", argv[i],
                         knownIds().c_str());
            return 2;
        }
        chosen.push_back(&it->second);
    }
    if (chosen.empty())
        for (const auto& [id, list] : listedExamples())
            chosen.push_back(&list);
    try {
        for (const auto* list : chosen)
            writeAll(*list, argv[1]);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "make_examples: %s\n", e.what());
        return 2;
    }
    return 0;
}
