// Writes the SPI example captures (captures/spi_*) from the generator.
// Usage: make_spi_examples OUTDIR
#include <cstdio>
#include <string>

#include "capture/capture_writer.h"
#include "spi_examples.h"

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: %s OUTDIR\n", argv[0]);
        return 2;
    }
    for (const auto& ex : busdecode::spiExamples()) {
        const std::string path = std::string(argv[1]) + "/" + ex.file;
        if (ex.format == "vcd")
            busdecode::writeVcd(ex.wave, path);
        else
            busdecode::writeCsv(ex.wave, path, busdecode::CsvDialect::SaleaeLogic2);
        std::string opts;
        for (const auto& [k, v] : ex.options)
            opts += " --opt " + k + "=" + v;
        std::printf("%s: %s\n  decode captures/%s --proto spi%s\n", path.c_str(),
                    ex.description.c_str(), ex.file.c_str(), opts.c_str());
    }
    return 0;
}
