// The analog channels of a sigrok session (.sr): `metadata` names them (`analog1=SDA`,
// `total analog=2`) and each channel's samples are little-endian float32 in chunks
// `analog-1-<channel>-<chunk>`. A session with logic probes goes to the logic reader.
#include <cstring>
#include <map>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <zip.h>

#include "analog_capture.h"
#include "core/options.h"
#include "readers.h"

namespace busdecode {

namespace {

std::string trimmed(std::string s) {
    while (!s.empty() && (s.back() == ' ' || s.back() == '\r' || s.back() == '\t'))
        s.pop_back();
    std::size_t b = 0;
    while (b < s.size() && (s[b] == ' ' || s[b] == '\t'))
        ++b;
    return s.substr(b);
}

std::map<std::string, std::string> readMetadata(zip_t* zip) {
    std::map<std::string, std::string> out;
    zip_file_t* f = zip_fopen(zip, "metadata", 0);
    if (!f) return out;
    std::string text;
    char buf[4096];
    for (zip_int64_t n; (n = zip_fread(f, buf, sizeof buf)) > 0 && text.size() < (1 << 20);)
        text.append(buf, std::size_t(n));
    zip_fclose(f);
    for (std::size_t b = 0; b < text.size();) {
        std::size_t e = text.find('\n', b);
        if (e == std::string::npos) e = text.size();
        const std::string line = text.substr(b, e - b);
        if (const auto eq = line.find('='); eq != std::string::npos)
            out[trimmed(line.substr(0, eq))] = trimmed(line.substr(eq + 1));
        b = e + 1;
    }
    return out;
}

class SrAnalogSamples : public SampleSource {
public:
    SrAnalogSamples(zip_t* zip, std::string name, double rate, std::vector<AnalogChannel> ch)
        : zip_(zip), name_(std::move(name)), rate_(rate), channels_(std::move(ch)) {
        streams_.resize(channels_.size());
        for (std::size_t c = 0; c < channels_.size(); ++c)
            open(c);
    }
    ~SrAnalogSamples() override {
        for (auto& s : streams_)
            if (s.file) zip_fclose(s.file);
        zip_discard(zip_);
    }

    const std::vector<AnalogChannel>& channels() const override { return channels_; }
    std::size_t slots() const override { return channels_.size(); }
    std::string formatName() const override { return "sigrok-sr"; }
    std::string fileName() const override { return name_; }
    double period() const override { return 1 / rate_; }
    std::uint64_t bytesRead() const override { return bytes_; }
    [[noreturn]] void fail(const std::string& what) const override {
        throw InputError(fmt::format("{}: sample {}: {}", name_, sample_, what));
    }

    bool next(double& t, float* values) override {
        for (std::size_t c = 0; c < streams_.size(); ++c)
            if (!take(c, values[c])) {
                if (c > 0) fail("analog channels of different lengths");
                return false;
            }
        t = double(sample_++) / rate_;
        bytes_ += 4 * streams_.size();
        return true;
    }

private:
    struct Stream {
        zip_file_t* file = nullptr;
        int chunk = 0;
        std::vector<float> buf;
        std::size_t at = 0;
    };

    // The channel's next chunk; false when there is none.
    bool open(std::size_t c) {
        Stream& s = streams_[c];
        if (s.file) zip_fclose(s.file);
        ++s.chunk;
        const std::string entry = fmt::format("analog-1-{}-{}", channels_[c].slot + 1, s.chunk);
        s.file = zip_fopen(zip_, entry.c_str(), 0);
        return s.file != nullptr;
    }

    bool take(std::size_t c, float& v) {
        Stream& s = streams_[c];
        while (s.at == s.buf.size()) {
            if (!s.file) return false;
            s.buf.resize(16384);
            const zip_int64_t n = zip_fread(s.file, s.buf.data(), s.buf.size() * sizeof(float));
            if (n < 0) fail(fmt::format("cannot read analog channel {}", channels_[c].name));
            s.buf.resize(std::size_t(n) / sizeof(float));
            s.at = 0;
            if (n == 0 && !open(c)) return false;
        }
        std::memcpy(&v, &s.buf[s.at++], sizeof v);  // sigrok writes little-endian floats
        return true;
    }

    zip_t* zip_;
    std::string name_;
    double rate_;
    std::vector<AnalogChannel> channels_;
    std::vector<Stream> streams_;
    std::uint64_t sample_ = 0, bytes_ = 0;
};

}  // namespace

std::unique_ptr<CaptureReader> openSrAnalogIfAnalog(const std::string& path,
                                                    const std::string& name,
                                                    const OpenOptions& opts) {
    int err = 0;
    zip_t* zip = zip_open(path.c_str(), ZIP_RDONLY, &err);
    if (!zip) return nullptr;  // the logic reader words the error
    const auto meta = readMetadata(zip);
    const auto total = meta.find("total analog");
    if (meta.count("unitsize") || total == meta.end()) {
        zip_discard(zip);
        return nullptr;
    }
    const auto rate = meta.find("samplerate");
    const double hz = rate == meta.end() ? 0 : double(parseRateHz(rate->second));
    const int n = std::atoi(total->second.c_str());
    if (!(hz > 0) || n <= 0 || n > 64) {
        zip_discard(zip);
        throw InputError(fmt::format("{}: analog session without a samplerate or channels", name));
    }
    std::vector<AnalogChannel> channels;
    for (int i = 0; i < n; ++i) {
        const auto it = meta.find(fmt::format("analog{}", i + 1));
        const std::string ch = it == meta.end() ? fmt::format("A{}", i) : it->second;
        channels.push_back({ch, ch, std::size_t(i), -1});
    }
    return analogReader(std::make_unique<SrAnalogSamples>(zip, name, hz, std::move(channels)),
                        opts);
}

}  // namespace busdecode
