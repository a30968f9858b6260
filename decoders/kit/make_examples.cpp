// Writes the decoders' example captures into CAPTURE_DIR exactly as they are committed:
//   make_examples CAPTURE_DIR [ID...]      (no ID: every decoder built)
// Their golden outputs come from one place: tests/golden/golden.py --write BIN_DIR.
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "example.h"

// Each decoder's list, when that decoder is built (BUSDECODE_DECODERS may leave it out).
#if __has_include("bissc_examples.h")
#include "bissc_examples.h"
#endif
#if __has_include("spi_examples.h")
#include "spi_examples.h"
#endif
#if __has_include("ssi_examples.h")
#include "ssi_examples.h"
#endif
#if __has_include("tmc8100_examples.h")
#include "tmc8100_examples.h"
#endif
#if __has_include("tmcl_examples.h")
#include "tmcl_examples.h"
#endif
#if __has_include("uart_examples.h")
#include "uart_examples.h"
#endif

using namespace busdecode;

namespace {

using Captures = std::vector<ExampleCapture>;

// The examples without their truth: all a writer needs.
template <class Truth>
Captures captures(const std::vector<Example<Truth>>& all) {
    return {all.begin(), all.end()};
}

struct DecoderExamples {
    const char* id;
    Captures (*make)();
};

const DecoderExamples kDecoders[] = {
#if __has_include("bissc_examples.h")
    {"bissc", [] { return captures(bisscExamples()); }},
#endif
#if __has_include("spi_examples.h")
    {"spi", [] { return captures(spiExamples()); }},
#endif
#if __has_include("ssi_examples.h")
    {"ssi", [] { return captures(ssiExamples()); }},
#endif
#if __has_include("tmc8100_examples.h")
    {"tmc8100", [] { return captures(tmc8100Examples()); }},
#endif
#if __has_include("tmcl_examples.h")
    {"tmcl", [] { return captures(tmclExamples()); }},
#endif
#if __has_include("uart_examples.h")
    {"uart", [] { return captures(uartExamples()); }},
#endif
};

const DecoderExamples* find(const std::string& id) {
    for (const auto& d : kDecoders)
        if (id == d.id) return &d;
    return nullptr;
}

std::string knownIds() {
    std::string ids;
    for (const auto& d : kDecoders)
        ids += std::string(ids.empty() ? "" : ", ") + d.id;
    return ids;
}

void writeAll(const DecoderExamples& d, const std::string& dir) {
    for (const auto& ex : d.make()) {
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
    std::vector<const DecoderExamples*> chosen;
    for (int i = 2; i < argc; ++i) {
        const DecoderExamples* d = find(argv[i]);
        if (!d) {
            std::fprintf(stderr, "make_examples: no decoder '%s' (ids: %s)\n", argv[i],
                         knownIds().c_str());
            return 2;
        }
        chosen.push_back(d);
    }
    if (chosen.empty())
        for (const auto& d : kDecoders)
            chosen.push_back(&d);
    try {
        for (const auto* d : chosen)
            writeAll(*d, argv[1]);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "make_examples: %s\n", e.what());
        return 2;
    }
    return 0;
}
