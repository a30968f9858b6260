// writeFst: a Waveform as an FST file through fstapi's writer, the lines as 1-bit wires in
// scope `busdecode` (as writeVcd declares them), for round trips through the FST reader.
// The timescale is the largest power of ten that holds every tick exactly.
#include <cstdio>
#include <filesystem>

#include <fmt/format.h>
#include <unistd.h>

#include "capture_writer.h"
#include "core/options.h"
#include "fst_api.h"
#include "fstapi.h"

namespace busdecode {

namespace {

// Units of 10^exponent s and ticks per unit: one tick = `multiplier` units, exactly when
// some exponent down to -18 allows it, else rounded to 1 fs.
struct FstScale {
    int exponent = -15;
    __int128 multiplier = 0;  // 0: round ticks to femtoseconds
};

FstScale scaleOf(const Timebase& tb) {
    __int128 num = tb.num;  // seconds per tick = num / den
    for (int e = 0; e >= -18; --e, num *= 10)
        if (num % tb.den == 0) return {e, num / tb.den};
    return {};
}

std::uint64_t unitsOf(Tick t, const Timebase& tb, const FstScale& s) {
    if (s.multiplier) return std::uint64_t(__int128(t) * s.multiplier);
    const __int128 fs = (__int128(t) * tb.num * 1'000'000'000'000'000 + tb.den / 2) / tb.den;
    return std::uint64_t(fs);
}

void emitAll(void* ctx, const Waveform& w, const FstScale& s, const std::vector<fstHandle>& h) {
    fstWriterEmitTimeChange(ctx, unitsOf(w.start, w.timebase, s));
    for (std::size_t i = 0; i < h.size(); ++i)
        fstWriterEmitValueChange(ctx, h[i], i < w.initial.size() && w.initial[i] ? "1" : "0");
    std::size_t in_block = 0;
    for (const Edge& e : w.edges) {
        // Blocks of about 2^20 changes: a reader holds one block at a time.
        if (++in_block == (std::size_t(1) << 20)) {
            fstWriterFlushContext(ctx);
            in_block = 0;
        }
        fstWriterEmitTimeChange(ctx, unitsOf(e.t, w.timebase, s));
        fstWriterEmitValueChange(ctx, h[e.line], e.level ? "1" : "0");
    }
    fstWriterEmitTimeChange(ctx, unitsOf(std::max(w.end, w.start), w.timebase, s));
}

}  // namespace

void writeFst(const Waveform& w, const std::string& path) {
    const auto dir = std::filesystem::path(path).parent_path();
    std::string tmp =
        ((dir.empty() ? std::filesystem::path(".") : dir) / ".busdecode-fst-XXXXXX").string();
    const int fd = mkstemp(tmp.data());
    if (fd < 0) throw InputError(fmt::format("{}: cannot create a file beside it", path));
    ::close(fd);
    void* ctx = fstWriterCreate(tmp.c_str(), 1);
    if (!ctx) {
        std::remove(tmp.c_str());
        throw InputError(fmt::format("{}: fstapi cannot write it", path));
    }
    const FstScale s = scaleOf(w.timebase);
    fstWriterSetPackType(ctx, FST_WR_PT_LZ4);
    fstWriterSetVersion(ctx, "busdecode");
    fstWriterSetTimescale(ctx, s.exponent);
    fstWriterSetScope(ctx, FST_ST_VCD_MODULE, "busdecode", nullptr);
    std::vector<fstHandle> handles;
    for (const auto& name : w.names)
        handles.push_back(
            fstWriterCreateVar(ctx, FST_VT_VCD_WIRE, FST_VD_IMPLICIT, 1, name.c_str(), 0));
    fstWriterSetUpscope(ctx);
    emitAll(ctx, w, s, handles);
    fstWriterClose(ctx);
    std::error_code ec;
    std::filesystem::rename(tmp, path, ec);
    if (ec) {
        std::remove(tmp.c_str());
        throw InputError(fmt::format("{}: cannot write it: {}", path, ec.message()));
    }
}

}  // namespace busdecode
