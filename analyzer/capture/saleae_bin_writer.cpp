// writeSaleaeBin: a Waveform as Saleae Logic 2 exports digital channels in binary, one
// `digital_N.bin` per line in a folder, version 0 or 1 (one chunk at the waveform's
// sample rate), for round trips through the reader; analog channels as `analog_N.bin`.
#include <filesystem>

#include <fmt/format.h>

#include "capture_writer.h"
#include "core/atomic_file.h"

namespace busdecode {

namespace {

template <class T>
void put(AtomicFile& out, T v) {
    out.put(std::string_view(reinterpret_cast<const char*>(&v), sizeof v));
}

}  // namespace

void writeSaleaeBin(const Waveform& w, const std::string& dir, int version) {
    std::filesystem::create_directories(dir);
    const double tick = double(w.timebase.num) / double(w.timebase.den);
    const double begin = double(w.start) * tick, end = double(w.end) * tick;
    for (std::uint32_t l = 0; l < w.names.size(); ++l) {
        std::vector<double> times;
        for (const Edge& e : w.edges)
            if (e.line == l) times.push_back(double(e.t) * tick);
        AtomicFile out(fmt::format("{}/digital_{}.bin", dir, l));
        out.put("<SALEAE>");
        put(out, std::int32_t(version));
        put(out, std::int32_t(0));  // digital
        if (version == 1) put(out, std::uint64_t(1));
        put(out, std::uint32_t(l < w.initial.size() && w.initial[l]));
        if (version == 1) put(out, double(w.timebase.den) / double(w.timebase.num));
        put(out, begin);
        put(out, end);
        put(out, std::uint64_t(times.size()));
        for (double t : times)
            put(out, t);
        out.commit();
    }
}

void writeSaleaeAnalogBin(const Waveform& w, const std::string& dir, double volts, int version) {
    std::filesystem::create_directories(dir);
    const double period = double(w.timebase.num) / double(w.timebase.den);
    const auto samples = std::uint64_t(std::max<Tick>(w.end - w.start, 0) + 1);
    const std::uint64_t first_part = version == 1 ? samples / 2 : samples;
    for (std::uint32_t l = 0; l < w.names.size(); ++l) {
        AtomicFile out(fmt::format("{}/analog_{}.bin", dir, l));
        out.put("<SALEAE>");
        put(out, std::int32_t(version));
        put(out, std::int32_t(1));  // analog
        auto waveformHeader = [&](Tick from, std::uint64_t n) {
            put(out, double(from) * period);
            if (version == 1) put(out, double(w.start) * period);  // the trigger time
            if (version == 1)
                put(out, 1 / period);
            else
                put(out, std::uint64_t(w.timebase.den / w.timebase.num));
            put(out, std::uint64_t(1));  // downsample
            put(out, n);
        };
        if (version == 1) put(out, std::uint64_t(2));  // waveforms
        waveformHeader(w.start, first_part);
        bool level = l < w.initial.size() && w.initial[l];
        std::size_t k = 0;
        while (k < w.edges.size() && w.edges[k].t <= w.start)
            if (w.edges[k++].line == l) level = w.edges[k - 1].level;
        for (Tick t = w.start; t <= w.end; ++t) {
            if (version == 1 && std::uint64_t(t - w.start) == first_part)
                waveformHeader(t, samples - first_part);
            for (; k < w.edges.size() && w.edges[k].t <= t; ++k)
                if (w.edges[k].line == l) level = w.edges[k].level;
            put(out, float(level ? volts : 0.0));
        }
        out.commit();
    }
}

}  // namespace busdecode
