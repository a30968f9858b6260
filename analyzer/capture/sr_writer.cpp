// Writes a Waveform as a sigrok session (.sr), as PulseView and `sigrok-cli -O srzip`
// do: a ZIP holding `version` ("2"), an INI `metadata` and the samples in deflated
// chunks `logic-1-1`, `logic-1-2`, ... of 4 MiB, one little-endian word of `unitsize`
// bytes per sample, probe N in bit N-1. A chunk's samples are made when libzip reads
// it, so the writer holds one chunk at a time, not the capture. libzip writes the
// archive beside the target and renames it into place at zip_close(): a reader never
// sees half a file, and a failed write leaves none.
#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <zip.h>

#include "capture_writer.h"
#include "core/options.h"

namespace busdecode {

namespace {

constexpr std::size_t kChunkBytes = 4 << 20;  // sigrok's chunk size

// One chunk: samples [first, first + samples), made by `render` when libzip reads it.
struct ChunkSource {
    const SrSampleWriter* render;
    std::uint64_t first;
    std::size_t samples;
    std::size_t unit;
    std::vector<std::uint8_t> data;
    std::size_t at = 0;
    zip_error_t error;

    void make() {
        data.resize(samples * unit);
        (*render)(first, samples, data.data());
    }
};

zip_int64_t chunkCallback(void* state, void* data, zip_uint64_t len, zip_source_cmd_t cmd) {
    auto* c = static_cast<ChunkSource*>(state);
    switch (cmd) {
        case ZIP_SOURCE_OPEN:
            // No exception may cross libzip's C frames: it becomes libzip's error.
            try {
                c->make();
            } catch (const std::bad_alloc&) {
                zip_error_set(&c->error, ZIP_ER_MEMORY, 0);
                return -1;
            } catch (...) {
                zip_error_set(&c->error, ZIP_ER_INTERNAL, 0);
                return -1;
            }
            c->at = 0;
            return 0;
        case ZIP_SOURCE_READ: {
            const std::size_t n = std::min<std::size_t>(len, c->data.size() - c->at);
            std::memcpy(data, c->data.data() + c->at, n);
            c->at += n;
            return zip_int64_t(n);
        }
        case ZIP_SOURCE_CLOSE:
            std::vector<std::uint8_t>().swap(c->data);
            return 0;
        case ZIP_SOURCE_STAT: {
            auto* st = static_cast<zip_stat_t*>(data);
            zip_stat_init(st);
            st->size = c->samples * c->unit;
            st->valid |= ZIP_STAT_SIZE;
            return sizeof(zip_stat_t);
        }
        case ZIP_SOURCE_ERROR:
            return zip_error_to_data(&c->error, data, len);
        case ZIP_SOURCE_FREE:
            zip_error_fini(&c->error);
            delete c;
            return 0;
        case ZIP_SOURCE_SUPPORTS:
            return zip_source_make_command_bitmap(ZIP_SOURCE_OPEN, ZIP_SOURCE_READ,
                                                  ZIP_SOURCE_CLOSE, ZIP_SOURCE_STAT,
                                                  ZIP_SOURCE_ERROR, ZIP_SOURCE_FREE, -1);
        default:
            zip_error_set(&c->error, ZIP_ER_OPNOTSUPP, 0);
            return -1;
    }
}

// INI-safe: one line, no control characters.
std::string iniValue(std::string v) {
    for (auto& c : v)
        if (static_cast<unsigned char>(c) < ' ') c = '_';
    return v;
}

}  // namespace

void writeSrSamples(const std::string& path, const std::vector<std::string>& names,
                    std::int64_t rate, std::uint64_t samples, const SrSampleWriter& render) {
    if (names.empty() || names.size() > 64)
        throw std::invalid_argument("writeSr: a session holds 1 to 64 lines");
    if (rate <= 0) throw std::invalid_argument("writeSr: the sample rate must be positive");
    const std::size_t unit = (names.size() + 7) / 8;

    std::string meta = fmt::format(
        "[global]\nsigrok version=busdecode\n\n[device 1]\ncapturefile=logic-1\n"
        "total probes={}\nsamplerate={}\ntotal analog=0\n",
        names.size(), sampleRateText(rate));
    for (std::size_t i = 0; i < names.size(); ++i)  // a line not acquired has no name
        if (!names[i].empty()) meta += fmt::format("probe{}={}\n", i + 1, iniValue(names[i]));
    meta += fmt::format("unitsize={}\n", unit);

    int err = 0;
    zip_t* z = zip_open(path.c_str(), ZIP_CREATE | ZIP_TRUNCATE, &err);
    if (!z) {
        zip_error_t ze;
        zip_error_init_with_code(&ze, err);
        const std::string msg = zip_error_strerror(&ze);
        zip_error_fini(&ze);
        throw InputError(fmt::format("{}: cannot write: {}", path, msg));
    }
    // Whatever stops the write (an error, an exception) discards the archive: libzip has
    // written nothing yet, and never will.
    struct Discard {
        zip_t* z;
        ~Discard() {
            if (z) zip_discard(z);
        }
    } guard{z};
    auto fail = [&](const std::string& what) {
        throw InputError(fmt::format("{}: cannot write {}: {}", path, what, zip_strerror(z)));
    };
    auto addText = [&](const char* name, const std::string& text) {
        // libzip reads the buffer at zip_close(): it gets a copy of its own to free.
        void* copy = std::malloc(text.size() ? text.size() : 1);
        if (!copy) throw std::bad_alloc();
        std::memcpy(copy, text.data(), text.size());
        zip_source_t* s = zip_source_buffer(z, copy, text.size(), 1);
        if (!s) {
            std::free(copy);
            fail(name);
        }
        if (zip_file_add(z, name, s, ZIP_FL_OVERWRITE) < 0) {
            zip_source_free(s);
            fail(name);
        }
    };
    addText("version", "2");
    addText("metadata", meta);

    const std::size_t per_chunk = kChunkBytes / unit;
    int index = 1;
    for (std::uint64_t first = 0; first < samples; first += per_chunk, ++index) {
        const auto n = std::size_t(std::min<std::uint64_t>(samples - first, per_chunk));
        auto* c = new ChunkSource{&render, first, n, unit, {}, 0, {}};
        zip_error_init(&c->error);
        zip_source_t* s = zip_source_function(z, chunkCallback, c);
        const std::string name = fmt::format("logic-1-{}", index);
        if (!s) {
            zip_error_fini(&c->error);
            delete c;
            fail(name);
        }
        if (zip_file_add(z, name.c_str(), s, ZIP_FL_OVERWRITE) < 0) {
            zip_source_free(s);  // frees c
            fail(name);
        }
    }
    if (zip_close(z) != 0) fail("the archive");
    guard.z = nullptr;  // closed and freed
}

SampleRenderer::SampleRenderer(const Waveform& w) : w_(w), unit_((w.names.size() + 7) / 8) {
    for (std::size_t i = 0; i < w.names.size() && i < 64; ++i)
        if (i >= w.initial.size() || w.initial[i]) start_levels_ |= std::uint64_t(1) << i;
    levels_ = start_levels_;
    at_ = w.start;
}

void SampleRenderer::render(std::uint64_t first, std::size_t n, std::uint8_t* out) {
    const Tick from = w_.start + Tick(first);
    if (from < at_) {  // an earlier stretch: start over
        k_ = 0;
        levels_ = start_levels_;
    }
    for (Tick t = from; t < from + Tick(n); ++t) {
        for (; k_ < w_.edges.size() && w_.edges[k_].t <= t; ++k_) {
            const std::uint64_t bit = std::uint64_t(1) << w_.edges[k_].line;
            levels_ = w_.edges[k_].level ? levels_ | bit : levels_ & ~bit;
        }
        for (std::size_t b = 0; b < unit_; ++b)
            *out++ = std::uint8_t(levels_ >> (8 * b));
    }
    at_ = from + Tick(n);
}

void writeSr(const Waveform& w, const std::string& path) {
    if (w.timebase.num <= 0 || w.timebase.den % w.timebase.num != 0)
        throw std::invalid_argument("writeSr: a session needs a timebase of one sample per tick");
    SampleRenderer r(w);
    const std::uint64_t samples = w.end >= w.start ? std::uint64_t(w.end - w.start) + 1 : 0;
    writeSrSamples(
        path, w.names, w.timebase.den / w.timebase.num, samples,
        [&r](std::uint64_t first, std::size_t n, std::uint8_t* out) { r.render(first, n, out); });
}

}  // namespace busdecode
