// Writes the BiSS-C example captures (captures/bissc_*, see bissc_examples.cpp) and
// their golden decoder output (captures/bissc_*.golden.jsonl), so both can be remade
// exactly:   make_bissc_examples <repo>/captures
#include <cstdio>
#include <fstream>
#include <string>

#include "bissc_decoder.h"
#include "bissc_examples.h"
#include "core/registry.h"
#include "sinks/jsonl_file.h"

using namespace busdecode;

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: make_bissc_examples CAPTURE_DIR\n");
        return 2;
    }
    Registry::instance().add(makeBisscFactory());
    const std::string dir = argv[1];
    for (const auto& ex : bisscExamples()) {
        const std::string path = dir + "/" + ex.file;
        if (ex.csv)
            writeCsv(ex.wave, path, CsvDialect::SigrokDense);
        else
            writeVcd(ex.wave, path);
        std::ofstream(dir + "/" + goldenPathFor(ex.file))
            << decodeFileToJsonl(path, "bissc", ex.options);
        std::printf("%s: %s\n", ex.file.c_str(), ex.description.c_str());
    }
    return 0;
}
