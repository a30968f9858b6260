// Reads a capture through its tokeniser alone, every signal selected, and prints how many
// edges it holds: bench/run.sh times this beside `decode` and `wc -l` on the same file,
// to show how much of decode's time is reading (no decoder, no event, no output).
//
//     read_capture FILE
#include <cstdio>
#include <exception>

#include "capture/capture_reader.h"

int main(int argc, char** argv) {
    using namespace busdecode;
    if (argc != 2) {
        std::fprintf(stderr, "usage: read_capture FILE\n");
        return 2;
    }
    try {
        auto reader = openCapture(argv[1], {});
        std::vector<LineRef> lines;
        for (int i = 0; i < int(reader->signals().size()); ++i)
            lines.push_back({i, -1});
        reader->select(lines);
        (void)reader->initialLevels();
        EdgeBlock block;
        unsigned long long edges = 0;
        while (reader->next(block))
            edges += block.edges.size();
        std::printf("%llu edges\n", edges);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "read_capture: %s\n", e.what());
        return 2;
    }
    return 0;
}
