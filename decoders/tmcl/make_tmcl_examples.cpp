// Writes the TMCL example captures (captures/tmcl_*.vcd) from the generator.
// Usage: make_tmcl_examples OUTDIR
#include <cstdio>
#include <string>

#include "capture/capture_writer.h"
#include "tmcl_examples.h"

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: %s OUTDIR\n", argv[0]);
        return 2;
    }
    for (const auto& ex : busdecode::tmclExamples()) {
        const std::string path = std::string(argv[1]) + "/" + ex.file;
        busdecode::writeVcd(ex.wave, path);
        std::printf("%s: %s\n", path.c_str(), ex.description.c_str());
    }
    return 0;
}
