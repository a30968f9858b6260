// Writes the SSI example captures (captures/ssi_*.vcd, .csv) from the generator.
// Usage: make_ssi_examples OUTDIR
#include <cstdio>
#include <string>

#include "capture/capture_writer.h"
#include "ssi_examples.h"

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: %s OUTDIR\n", argv[0]);
        return 2;
    }
    const std::string dir = argv[1];
    for (const auto& ex : busdecode::ssiExamples()) {
        const std::string path = dir + "/" + ex.file;
        if (ex.format == "vcd")
            busdecode::writeVcd(ex.gen.wave, path);
        else if (ex.format == "sigrok-csv")
            busdecode::writeCsv(ex.gen.wave, path, busdecode::CsvDialect::SigrokDense);
        else
            busdecode::writeCsv(ex.gen.wave, path, busdecode::CsvDialect::SaleaeLogic2);
        std::string opts;
        for (const auto& [k, v] : ex.options)
            opts += " --opt " + k + "=" + v;
        std::printf("%s: %s\n  decode %s --proto ssi%s\n", path.c_str(), ex.description.c_str(),
                    ex.file.c_str(), opts.c_str());
    }
    return 0;
}
