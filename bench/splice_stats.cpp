// Decodes a capture as `decode FILE --proto ID` does (nothing printed) and says how its
// pieces went (core/piece_speculation.h): how many came decoded ahead, how many of those
// were spliced in, and how many edges the decoding thread did not decode itself.
//
//     splice_stats FILE ID [PIECE_BYTES]   PIECE_BYTES: cut the file finer than decode does
//
// Errors are printed as one line, with exit status 2.
#include <cstdio>
#include <exception>
#include <string>

#include "bench_captures.h"
#include "capture/capture_reader.h"
#include "core/session.h"

int main(int argc, char** argv) {
    using namespace busdecode;
    if (argc < 3 || argc > 4) {
        std::fprintf(stderr, "usage: splice_stats FILE ID [PIECE_BYTES]\n");
        return 2;
    }
    try {
        bench::registerDecoders();
        OpenOptions opts;
        if (argc == 4) opts.vcd_piece_bytes = std::stoull(argv[3]);
        auto reader = openCapture(argv[1], opts);
        DecoderRequest request;
        request.proto = argv[2];
        Session session({request}, *reader, argv[1]);
        session.run();
        const Session::PieceStats s = session.pieceStats();
        const std::uint64_t edges = session.facts().edges;
        std::printf(
            "%s: %llu pieces decoded ahead, %llu spliced in; %llu of %llu edges (%.2f %%) "
            "not decoded again\n",
            argv[1], (unsigned long long)s.pieces, (unsigned long long)s.spliced,
            (unsigned long long)s.edges_ahead, (unsigned long long)edges,
            edges ? 100.0 * double(s.edges_ahead) / double(edges) : 0.0);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "splice_stats: %s\n", e.what());
        return 2;
    }
    return 0;
}
