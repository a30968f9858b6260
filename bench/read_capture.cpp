// Reads a capture through its tokeniser alone, every signal selected, and prints how many
// edges it holds: bench/run.sh times this beside `decode` and `wc -l` on the same file,
// to show how much of decode's time is reading (no decoder, no event, no output).
//
//     read_capture FILE
#include <cstdio>
#include <exception>

#include "read_edges.h"

int main(int argc, char** argv) {
    using namespace busdecode;
    if (argc != 2) {
        std::fprintf(stderr, "usage: read_capture FILE\n");
        return 2;
    }
    try {
        const unsigned long long edges = bench::readEdges(argv[1]);
        std::printf("%llu edges\n", edges);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "read_capture: %s\n", e.what());
        return 2;
    }
    return 0;
}
