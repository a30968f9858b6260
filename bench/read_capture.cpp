// Reads a capture through its tokeniser alone, every signal selected:
//
//     read_capture FILE                      prints how many edges it holds: bench/run.sh
//                                            times this beside decode and wc -l, to show
//                                            how much of decode's time is reading
//     read_capture --edges [--rate HZ] FILE  prints every edge (read_edges.h: printEdges),
//                                            to compare two builds' readers line for line
//     read_capture --prefetch FILE           the same count, read on two threads as decode
//                                            reads (a VCD in pieces on both, other formats
//                                            ahead on a second: read_edges.h), this thread
//                                            reading every edge: decode's floor
//
// Errors (unreadable or broken captures) are printed as one line, with exit status 2; with
// --edges also on stdout, so that two builds' outputs compare errors too.
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <string>

#include "read_edges.h"

int main(int argc, char** argv) {
    using namespace busdecode;
    bool edges = false;
    bool prefetch = false;
    OpenOptions opts;
    int i = 1;
    for (; i < argc - 1; ++i) {
        if (std::strcmp(argv[i], "--edges") == 0) {
            edges = true;
        } else if (std::strcmp(argv[i], "--prefetch") == 0) {
            prefetch = true;
        } else if (std::strcmp(argv[i], "--rate") == 0 && i + 2 < argc) {
            opts.rate_hz = std::atof(argv[++i]);
        } else {
            break;
        }
    }
    if (i != argc - 1) {
        std::fprintf(stderr, "usage: read_capture [--edges [--rate HZ] | --prefetch] FILE\n");
        return 2;
    }
    try {
        if (edges) {
            bench::printEdges(argv[i], opts, stdout);
        } else if (prefetch) {
            const bench::Touched n = bench::readEdgesAhead(argv[i]);
            std::printf("%llu edges (checksum %llu)\n", (unsigned long long)n.edges,
                        (unsigned long long)n.checksum);
        } else {
            const unsigned long long n = bench::readEdges(argv[i]);
            std::printf("%llu edges\n", n);
        }
    } catch (const std::exception& e) {
        if (edges) std::printf("error: %s\n", e.what());
        std::fprintf(stderr, "read_capture: %s\n", e.what());
        return 2;
    }
    return 0;
}
