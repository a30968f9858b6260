// Writes a Waveform as a DSView session (.dsl), as DSView saves a logic capture: a ZIP
// holding the `header` INI, an empty `decoders` list and per line the deflated
// bit-planes `L-<line>/<block>` (2^24 samples a block, LSB first, the last block cut to
// whole 64-bit words). The planes are made in memory: for generated test traffic.
#include <zip.h>

#include <fmt/format.h>

#include "capture_writer.h"
#include "core/options.h"

namespace busdecode {

namespace {

constexpr std::uint64_t kBlockSamples = std::uint64_t(1) << 24;

// Sets samples [from, to) of `words` to 1.
void setOnes(std::vector<std::uint64_t>& words, std::uint64_t from, std::uint64_t to) {
    for (std::uint64_t s = from; s < to;) {
        const std::uint64_t bit = s % 64, n = std::min<std::uint64_t>(64 - bit, to - s);
        const std::uint64_t ones = n == 64 ? ~std::uint64_t(0) : ((std::uint64_t(1) << n) - 1);
        words[s / 64] |= ones << bit;
        s += n;
    }
}

// The bit-plane of `line` over samples [first, first + n) (relative to the capture start).
std::string plane(const Waveform& w, std::uint32_t line, std::uint64_t first, std::uint64_t n) {
    std::vector<std::uint64_t> words((n + 63) / 64, 0);
    bool level = line < w.initial.size() && w.initial[line];
    std::uint64_t since = 0;  // relative to the capture start
    auto flush = [&](std::uint64_t until) {
        const std::uint64_t a = std::max(since, first), b = std::min(until, first + n);
        if (level && a < b) setOnes(words, a - first, b - first);
    };
    for (const Edge& e : w.edges) {
        if (e.line != line) continue;
        const std::uint64_t at = std::uint64_t(e.t - w.start);
        if (at >= first + n) break;
        flush(at);
        since = at;
        level = e.level;
    }
    flush(first + n);
    return std::string(reinterpret_cast<const char*>(words.data()), words.size() * 8);
}

}  // namespace

void writeDsl(const Waveform& w, const std::string& path) {
    if (w.timebase.num <= 0 || w.timebase.den % w.timebase.num != 0)
        throw std::invalid_argument("writeDsl: a session needs a timebase of one sample per tick");
    const std::uint64_t samples = w.end >= w.start ? std::uint64_t(w.end - w.start) + 1 : 0;
    const std::uint64_t blocks = (samples + kBlockSamples - 1) / kBlockSamples;
    std::string header = fmt::format(
        "[version]\nversion = 2\n[header]\ndriver = busdecode\ndevice mode = 0\n"
        "capturefile = data\ntotal samples = {}\ntotal probes = {}\ntotal blocks = {}\n"
        "samplerate = {}\ntrigger pos = 0\n",
        samples, w.names.size(), blocks, sampleRateText(w.timebase.den / w.timebase.num));
    for (std::size_t i = 0; i < w.names.size(); ++i)
        header += fmt::format("probe{} = {}\n", i, w.names[i]);
    std::vector<std::pair<std::string, std::string>> members = {{"header", header},
                                                                {"decoders", "[\n]\n"}};
    for (std::uint32_t l = 0; l < w.names.size(); ++l)
        for (std::uint64_t b = 0; b < blocks; ++b)
            members.push_back({fmt::format("L-{}/{}", l, b),
                               plane(w, l, b * kBlockSamples,
                                     std::min(kBlockSamples, samples - b * kBlockSamples))});
    int err = 0;
    zip_t* z = zip_open(path.c_str(), ZIP_CREATE | ZIP_TRUNCATE, &err);
    if (!z) throw InputError(fmt::format("{}: cannot create the session", path));
    for (const auto& [name, data] : members) {
        zip_source_t* src = zip_source_buffer(z, data.data(), data.size(), 0);
        if (!src || zip_file_add(z, name.c_str(), src, ZIP_FL_ENC_UTF_8) < 0) {
            if (src) zip_source_free(src);
            zip_discard(z);
            throw InputError(fmt::format("{}: cannot write {}", path, name));
        }
    }
    if (zip_close(z) != 0) {
        const std::string msg = zip_strerror(z);
        zip_discard(z);
        throw InputError(fmt::format("{}: cannot write the session: {}", path, msg));
    }
}

}  // namespace busdecode
