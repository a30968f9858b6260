// Writes the UART example captures (captures/uart_*) from the generator.
// Usage: make_uart_examples OUTDIR
#include <cstdio>
#include <string>

#include "capture/capture_writer.h"
#include "uart_examples.h"

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: %s OUTDIR\n", argv[0]);
        return 2;
    }
    for (const auto& ex : busdecode::uartExamples()) {
        const std::string path = std::string(argv[1]) + "/" + ex.file;
        if (path.ends_with(".csv"))
            busdecode::writeCsv(ex.wave, path, busdecode::CsvDialect::SigrokDense);
        else
            busdecode::writeVcd(ex.wave, path);
        std::printf("%s: %s\n", path.c_str(), ex.description.c_str());
    }
    return 0;
}
