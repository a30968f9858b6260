// Writes the SSI example captures (captures/ssi_*.vcd, .csv) from the generator, and
// beside each its golden output (ssi_*.golden.jsonl).
// Usage: make_ssi_examples OUTDIR
#include <cstdio>
#include <fstream>
#include <string>

#include "capture/capture_writer.h"
#include "core/registry.h"
#include "sinks/jsonl_file.h"
#include "ssi_examples.h"
#include "ssi_factory.h"

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: %s OUTDIR\n", argv[0]);
        return 2;
    }
    const std::string dir = argv[1];
    busdecode::Registry::instance().add(busdecode::makeSsiFactory());
    for (const auto& ex : busdecode::ssiExamples()) {
        const std::string path = dir + "/" + ex.file;
        if (ex.format == "vcd")
            busdecode::writeVcd(ex.gen.wave, path);
        else if (ex.format == "sigrok-csv")
            busdecode::writeCsv(ex.gen.wave, path, busdecode::CsvDialect::SigrokDense);
        else
            busdecode::writeCsv(ex.gen.wave, path, busdecode::CsvDialect::SaleaeLogic2);
        // The golden output: what `decode FILE --proto ssi --format jsonl` prints.
        std::ofstream(dir + "/" + busdecode::goldenPathFor(ex.file), std::ios::binary)
            << busdecode::decodeFileToJsonl(path, "ssi", ex.options);
        std::string opts;
        for (const auto& [k, v] : ex.options)
            opts += " --opt " + k + "=" + v;
        std::printf("%s: %s\n  decode %s --proto ssi%s\n", path.c_str(), ex.description.c_str(),
                    ex.file.c_str(), opts.c_str());
    }
    return 0;
}
