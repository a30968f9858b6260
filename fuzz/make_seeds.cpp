// fuzz_make_seeds OUTDIR: seed corpora for every fuzz target, made with the decoders'
// own generators (the benchmark buses, a few frames each): VCD and every CSV dialect
// written with the project's writers, .sr inputs in the sr target's structured form,
// and each decoder's input format for its own bus and for every other bus (the wrong
// protocol on the mapped lines). fuzz/run.sh adds the real captures beside them.
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "bench_captures.h"
#include "capture/capture_writer.h"
#include "capture/scope_csv_writer.h"
#include "core/registry.h"
#include "fuzz_harness.h"

namespace fs = std::filesystem;
using namespace busdecode;

namespace {

void put(const fs::path& path, const std::string& bytes) {
    fs::create_directories(path.parent_path());
    std::ofstream(path, std::ios::binary) << bytes;
}

std::string lower(std::string s) {
    for (auto& c : s)
        c = char(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

// `w` with its lines in the decoder's role order (a role no line matches by name or
// alias gets a constant high line; with `by_position` the lines are taken in order).
Waveform inRoleOrder(const Waveform& w, const DecoderInfo& info, bool by_position) {
    Waveform out;
    out.timebase = w.timebase;
    out.start = w.start;
    out.end = w.end;
    std::vector<int> src_of_role;
    for (std::size_t r = 0; r < info.roles.size(); ++r) {
        int src = -1;
        if (by_position) {
            src = r < w.names.size() ? int(r) : -1;
        } else {
            std::vector<std::string> names = {info.roles[r].name};
            names.insert(names.end(), info.roles[r].aliases.begin(), info.roles[r].aliases.end());
            for (std::size_t l = 0; l < w.names.size() && src < 0; ++l)
                for (const auto& n : names)
                    if (lower(w.names[l]) == lower(n)) src = int(l);
        }
        src_of_role.push_back(src);
        out.names.push_back(info.roles[r].name);
        out.initial.push_back(src >= 0 ? w.initial[std::size_t(src)] : 1);
    }
    for (const Edge& e : w.edges)
        for (std::size_t r = 0; r < src_of_role.size(); ++r)
            if (src_of_role[r] == int(e.line))
                out.edges.push_back({e.t, std::uint32_t(r), std::uint8_t(e.level)});
    return out;
}

// The sr target's structured input: metadata, NUL, flags, chunks (see reader_harness).
std::string srSeed(const Waveform& w) {
    std::string meta = "[global]\nsigrok version=0.5.2\n\n[device 1]\ncapturefile=logic-1\n";
    meta += "total probes=" + std::to_string(w.names.size()) + "\n";
    meta += "samplerate=" + std::to_string(std::int64_t(w.timebase.sampleRateHz())) + "\n";
    for (std::size_t i = 0; i < w.names.size(); ++i)
        meta += "probe" + std::to_string(i + 1) + "=" + w.names[i] + "\n";
    meta += "unitsize=1\n";
    std::string out = meta;
    out += '\0';
    out += char(0);
    std::uint8_t levels = 0;
    for (std::size_t i = 0; i < w.initial.size() && i < 8; ++i)
        levels |= std::uint8_t(w.initial[i] << i);
    std::string samples;
    std::size_t next = 0;
    for (Tick t = w.start; t < w.end && samples.size() < 8192; ++t) {
        while (next < w.edges.size() && w.edges[next].t <= t) {
            const Edge& e = w.edges[next++];
            if (e.line < 8)
                levels = std::uint8_t((levels & ~(1u << e.line)) | (unsigned(e.level) << e.line));
        }
        samples += char(levels);
    }
    for (std::size_t off = 0; off < samples.size(); off += 4096) {
        const std::string chunk = samples.substr(off, 4096);
        std::size_t n = chunk.size();
        do {  // varint length
            std::uint8_t b = n & 0x7f;
            n >>= 7;
            if (n) b |= 0x80;
            out += char(b);
        } while (n);
        out += chunk;
    }
    return out;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: fuzz_make_seeds OUTDIR\n");
        return 2;
    }
    const fs::path out = argv[1];
    bench::registerDecoders();
    fuzz::registerDecoders();
    for (const auto& id : bench::availableBuses()) {
        const bench::BenchBus bus = bench::makeBus(id, id == "uart" ? 8 : 3);
        const Waveform& w = bus.chunk;
        const fs::path tmp = out / "tmp";
        for (const char* d : {"tmp", "vcd", "csv_saleae", "csv_sigrok", "csv_plain"})
            fs::create_directories(out / d);
        writeVcd(w, (out / "vcd" / (id + ".vcd")).string());
        writeCsv(w, (out / "csv_saleae" / (id + ".csv")).string(), CsvDialect::SaleaeLogic2);
        if (w.timebase.num == 1 &&
            w.end - w.start < 20000) {  // dense dialects: short captures only
            writeCsv(w, (out / "csv_sigrok" / (id + ".csv")).string(), CsvDialect::SigrokDense);
            writeCsv(w, (out / "csv_plain" / (id + ".csv")).string(), CsvDialect::Plain);
            // Every scope dialect (read through the same content sniffing as Saleae's).
            AnalogStyle style;
            style.sample_ns = w.timebase.nsPerTick();
            style.rise_ns = 4 * style.sample_ns;
            style.snr_db = 24;
            style.differential = id == "uart";
            for (const ScopeDialect d : kScopeDialects)
                writeScopeCsv(
                    w, (out / "csv_saleae" / (id + "_" + scopeDialectName(d) + ".csv")).string(), d,
                    style);
        }
        put(out / "sr" / (id + ".bin"), srSeed(w));
        for (const auto* f : Registry::instance().all()) {
            const std::string target = "decoder_" + f->info().id;
            const bool own = f->info().id == id;
            const Waveform roles = inRoleOrder(w, f->info(), !own);
            const DecoderRequest req =
                own ? bus.requests.front() : DecoderRequest{f->info().id, {}, {}};
            put(out / target / (id + ".bin"), fuzz::encodeDecoderInput(f->info().id, roles, req));
        }
        fs::remove_all(tmp);
    }
    std::printf("seeds written to %s\n", out.string().c_str());
    return 0;
}
