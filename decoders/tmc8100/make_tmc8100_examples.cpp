// Writes the TMC8100 example captures (captures/tmc8100_*.vcd) from the generator.
// Usage: make_tmc8100_examples OUTDIR
#include <cstdio>
#include <string>

#include "capture/capture_writer.h"
#include "tmc8100_examples.h"

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: %s OUTDIR\n", argv[0]);
        return 2;
    }
    for (const auto& ex : busdecode::tmc8100Examples()) {
        const std::string path = std::string(argv[1]) + "/" + ex.file;
        busdecode::writeVcd(ex.wave, path);
        std::printf("%s: %s\n  %s\n", path.c_str(), ex.description.c_str(),
                    busdecode::decodeCommand("captures/" + ex.file, ex.requests).c_str());
    }
    return 0;
}
