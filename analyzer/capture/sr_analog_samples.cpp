// The analog channels of a sigrok session (.sr): `metadata` names them (`analog1=SDA`,
// `total analog=2`) and each channel's samples are little-endian float32 in chunks
// `analog-1-<channel>-<chunk>`. A session of logic probes alone goes to the logic reader
// (faster); a mixed one is read here, its probes as bits of the logic word's bytes.
#include <algorithm>
#include <cstring>
#include <map>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <zip.h>

#include "analog_capture.h"
#include "core/options.h"
#include "readers.h"
#include "session_ini.h"

namespace busdecode {

namespace {

// The session's `metadata` ("" where it has none: the logic reader words that error).
std::string metadataText(zip_t* zip) {
    std::string text;
    zip_file_t* f = zip_fopen(zip, "metadata", 0);
    if (!f) return text;
    char buf[4096];
    for (zip_int64_t n; (n = zip_fread(f, buf, sizeof buf)) > 0 && text.size() < (1 << 20);)
        text.append(buf, std::size_t(n));
    zip_fclose(f);
    return text;
}

// Where a session's samples are: each analog channel's chunks `analog-1-<N>-<chunk>`
// (N its number among all channels: after the probes in a mixed session), and the logic
// words' chunks `logic-1-<chunk>` (old sessions: one `logic-1`).
struct SrLayout {
    std::vector<AnalogChannel> channels;  // analog ones in slots 0.., then the probes
    std::vector<int> analog_number;       // N of each analog slot
    std::size_t unitsize = 0;             // bytes of a logic word, 0: no probes
    std::string logic_prefix = "logic-1";
};

class SrAnalogSamples : public SampleSource {
public:
    SrAnalogSamples(zip_t* zip, std::string name, double rate, SrLayout layout)
        : zip_(zip), name_(std::move(name)), rate_(rate), layout_(std::move(layout)) {
        const std::size_t analog = layout_.analog_number.size();
        streams_.resize(analog + (layout_.unitsize ? 1 : 0));
        for (std::size_t c = 0; c < streams_.size(); ++c) {
            streams_[c].prefix = c < analog ? fmt::format("analog-1-{}-", layout_.analog_number[c])
                                            : layout_.logic_prefix + "-";
            open(streams_[c]);
        }
        if (layout_.unitsize && !streams_.back().file) {  // one unnumbered chunk
            streams_.back().file = zip_fopen(zip_, layout_.logic_prefix.c_str(), 0);
            streams_.back().single = true;
        }
    }
    ~SrAnalogSamples() override {
        for (auto& s : streams_)
            if (s.file) zip_fclose(s.file);
        zip_discard(zip_);
    }

    const std::vector<AnalogChannel>& channels() const override { return layout_.channels; }
    std::size_t slots() const override { return layout_.analog_number.size() + layout_.unitsize; }
    std::string formatName() const override { return "sigrok-sr"; }
    std::string fileName() const override { return name_; }
    double period() const override { return 1 / rate_; }
    std::uint64_t bytesRead() const override { return bytes_; }
    [[noreturn]] void fail(const std::string& what) const override {
        throw InputError(fmt::format("{}: sample {}: {}", name_, sample_, what));
    }

    bool next(double& t, float* values) override {
        const std::size_t analog = layout_.analog_number.size();
        for (std::size_t c = 0; c < streams_.size(); ++c) {
            unsigned char bytes[8];
            const std::size_t n = c < analog ? 4 : layout_.unitsize;
            if (!take(streams_[c], bytes, n)) {
                if (c > 0) fail("analog and logic channels of different lengths");
                // The others read to their ends too: libzip checks a CRC only there.
                for (std::size_t o = 1; o < streams_.size(); ++o)
                    if (take(streams_[o], bytes, 1))
                        fail("analog and logic channels of different lengths");
                return false;
            }
            if (c < analog)
                std::memcpy(&values[c], bytes, 4);  // sigrok writes little-endian floats
            else
                for (std::size_t b = 0; b < n; ++b)  // a byte a slot: exact in a float
                    values[analog + b] = float(bytes[b]);
            bytes_ += n;
        }
        t = double(sample_++) / rate_;
        return true;
    }

private:
    struct Stream {
        std::string prefix;
        zip_file_t* file = nullptr;
        int chunk = 0;
        bool single = false;
        std::vector<unsigned char> buf;
        std::size_t at = 0;
    };

    // The stream's next chunk; false when there is none.
    bool open(Stream& s) {
        if (s.file) zip_fclose(s.file);
        s.file = nullptr;
        if (s.single) return false;
        s.file = zip_fopen(zip_, (s.prefix + std::to_string(++s.chunk)).c_str(), 0);
        return s.file != nullptr;
    }

    bool take(Stream& s, unsigned char* out, std::size_t n) {
        for (std::size_t i = 0; i < n; ++i) {
            while (s.at == s.buf.size()) {
                if (!s.file) return false;
                s.buf.resize(65536);
                const zip_int64_t got = zip_fread(s.file, s.buf.data(), s.buf.size());
                if (got < 0)
                    fail(fmt::format("{}{} is corrupt: {}", s.prefix, s.chunk,
                                     zip_error_strerror(zip_file_get_error(s.file))));
                s.buf.resize(std::size_t(got));
                s.at = 0;
                if (got == 0 && !open(s)) return false;
            }
            out[i] = s.buf[s.at++];
        }
        return true;
    }

    zip_t* zip_;
    std::string name_;
    double rate_;
    SrLayout layout_;
    std::vector<Stream> streams_;
    std::uint64_t sample_ = 0, bytes_ = 0;
};

}  // namespace

namespace {

// The session's channels: its analog ones, numbered by their `analogN` keys (after the
// probes in a mixed session), then its probes, a byte of the logic word a slot.
SrLayout layoutOf(const SrMetadata& meta, int analog, const std::string& name) {
    SrLayout l;
    const int probes = meta.number("total probes");
    for (const auto& [key, value] : meta.keys())  // in the order of the keys: sorted below
        if (key.rfind("analog", 0) == 0 && std::atoi(key.c_str() + 6) > 0)
            l.analog_number.push_back(std::atoi(key.c_str() + 6));
    std::sort(l.analog_number.begin(), l.analog_number.end());
    if (int(l.analog_number.size()) != analog) {
        l.analog_number.clear();
        for (int i = 0; i < analog; ++i)
            l.analog_number.push_back(probes + i + 1);
    }
    for (std::size_t i = 0; i < l.analog_number.size(); ++i) {
        const std::string* named = meta.find(fmt::format("analog{}", l.analog_number[i]));
        const std::string ch = named ? *named : fmt::format("A{}", i);
        l.channels.push_back({ch, ch, i, -1});
    }
    if (probes <= 0) return l;
    l.unitsize = std::size_t(meta.number("unitsize"));
    if (l.unitsize < 1 || l.unitsize > 8 || std::size_t(probes) > 8 * l.unitsize)
        throw InputError(
            fmt::format("{}: {} probes do not fit in unitsize={}", name, probes, l.unitsize));
    for (int bit = 0; bit < probes; ++bit) {
        const std::string ch = meta.probeName(bit);
        l.channels.push_back({ch, ch, std::size_t(analog + bit / 8), bit % 8});
    }
    if (const std::string* file = meta.find("capturefile")) l.logic_prefix = *file;
    return l;
}

}  // namespace

std::unique_ptr<CaptureReader> openSrAnalogIfAnalog(const std::string& path,
                                                    const std::string& name,
                                                    const OpenOptions& opts) {
    int err = 0;
    zip_t* zip = zip_open(path.c_str(), ZIP_RDONLY, &err);
    if (!zip) return nullptr;  // the logic reader words the error
    const SrMetadata meta(metadataText(zip));
    const int analog = meta.number("total analog");
    if (analog <= 0) {  // logic probes only: the logic reader's, which is faster
        zip_discard(zip);
        return nullptr;
    }
    const std::string* rate = meta.find("samplerate");
    const double hz = rate ? double(parseRateHz(*rate)) : 0;
    if (!(hz > 0) || analog > 64) {
        zip_discard(zip);
        throw InputError(fmt::format("{}: analog session without a samplerate or channels", name));
    }
    SrLayout layout;
    try {
        layout = layoutOf(meta, analog, name);
    } catch (...) {
        zip_discard(zip);  // the source owns the archive once it is made
        throw;
    }
    return analogReader(std::make_unique<SrAnalogSamples>(zip, name, hz, std::move(layout)), opts);
}

}  // namespace busdecode
