// compressFile: a capture written by the other writers, compressed as gzip, xz or zstd
// tools write it, for round trips through the decompressing input.
#include <cstdio>
#include <stdexcept>
#include <vector>

#include <lzma.h>
#include <zlib.h>
#include <zstd.h>

#include <fmt/format.h>

#include "capture_writer.h"
#include "core/atomic_file.h"
#include "core/options.h"

namespace busdecode {

namespace {

// Compresses `in` into `out` a buffer at a time with one codec's step: step(input, last,
// sink) hands every output byte to sink.
using Sink = std::function<void(const char*, std::size_t)>;
using Step = std::function<void(std::string_view, bool, const Sink&)>;

Step gzipStep(z_stream& z) {
    if (deflateInit2(&z, 6, Z_DEFLATED, 15 + 16, 8, Z_DEFAULT_STRATEGY) != Z_OK)
        throw std::bad_alloc();
    return [&z](std::string_view in, bool last, const Sink& sink) {
        char out[1 << 16];
        z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(in.data()));
        z.avail_in = uInt(in.size());
        int rc;
        do {
            z.next_out = reinterpret_cast<Bytef*>(out);
            z.avail_out = sizeof out;
            rc = deflate(&z, last ? Z_FINISH : Z_NO_FLUSH);
            sink(out, sizeof out - z.avail_out);
        } while (z.avail_out == 0 || (last && rc != Z_STREAM_END));
    };
}

Step xzStep(lzma_stream& s) {
    if (lzma_easy_encoder(&s, 6, LZMA_CHECK_CRC64) != LZMA_OK) throw std::bad_alloc();
    return [&s](std::string_view in, bool last, const Sink& sink) {
        std::uint8_t out[1 << 16];
        s.next_in = reinterpret_cast<const std::uint8_t*>(in.data());
        s.avail_in = in.size();
        lzma_ret rc;
        do {
            s.next_out = out;
            s.avail_out = sizeof out;
            rc = lzma_code(&s, last ? LZMA_FINISH : LZMA_RUN);
            sink(reinterpret_cast<const char*>(out), sizeof out - s.avail_out);
        } while (s.avail_out == 0 || (last && rc != LZMA_STREAM_END));
    };
}

Step zstdStep(ZSTD_CCtx* c) {
    return [c](std::string_view in, bool last, const Sink& sink) {
        char out[1 << 16];
        ZSTD_inBuffer ib{in.data(), in.size(), 0};
        std::size_t left;
        do {
            ZSTD_outBuffer ob{out, sizeof out, 0};
            left = ZSTD_compressStream2(c, &ob, &ib, last ? ZSTD_e_end : ZSTD_e_continue);
            if (ZSTD_isError(left)) throw std::runtime_error(ZSTD_getErrorName(left));
            sink(out, ob.pos);
        } while (ib.pos < ib.size || (last && left != 0));
    };
}

}  // namespace

void compressFile(const std::string& in_path, const std::string& out_path, Compression kind) {
    if (kind != Compression::Gzip && kind != Compression::Xz && kind != Compression::Zstd)
        throw std::invalid_argument("compressFile: not a compression");  // CrLineEnds, None
    std::FILE* in = std::fopen(in_path.c_str(), "rb");
    if (!in) throw InputError(fmt::format("{}: cannot open", in_path));
    z_stream z{};
    lzma_stream s = LZMA_STREAM_INIT;
    ZSTD_CCtx* c = ZSTD_createCCtx();
    try {
        const Step step = kind == Compression::Gzip ? gzipStep(z)
                          : kind == Compression::Xz ? xzStep(s)
                                                    : zstdStep(c);
        AtomicFile out(out_path);
        const Sink sink = [&](const char* p, std::size_t n) { out.put({p, n}); };
        std::vector<char> buf(1 << 20);
        for (;;) {
            const std::size_t n = std::fread(buf.data(), 1, buf.size(), in);
            const bool last = n < buf.size();
            step({buf.data(), n}, last, sink);
            if (last) break;
        }
        out.commit();
    } catch (...) {
        deflateEnd(&z);
        lzma_end(&s);
        ZSTD_freeCCtx(c);
        std::fclose(in);
        throw;
    }
    deflateEnd(&z);
    lzma_end(&s);
    ZSTD_freeCCtx(c);
    std::fclose(in);
}

}  // namespace busdecode
