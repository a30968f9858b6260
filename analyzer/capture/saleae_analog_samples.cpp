// Saleae Logic 2 binary export, analog channels (Saleae's "Binary Export Format"): one
// file per channel, `analog_N.bin`: "<SALEAE>", int32 version, int32 type 1, then
// - version 0: f64 begin time (s), u64 sample rate, u64 downsample, u64 n, n float32 volts;
// - version 1 (the "2025 update"): u64 waveform count, per waveform f64 begin, f64 trigger
//   time, f64 sample rate, i64 downsample, u64 n, n float32 volts; gaps between waveforms
//   hold no data;
// all little-endian; sample k of a waveform at begin + k * downsample / rate. A folder of
// such files (or one of them) is one capture, its channels read side by side (their
// waveforms alike) and turned into edges by the analog layer (analog_capture.h).
#include <cmath>
#include <cstdio>
#include <cstring>

#include <fmt/format.h>

#include "analog_capture.h"
#include "core/options.h"
#include "readers.h"

namespace busdecode {

namespace {

constexpr long kCommonHeaderBytes = 16;
constexpr long kV0HeaderBytes = kCommonHeaderBytes + 8 + 8 + 8 + 8;
constexpr long kV1WaveformHeaderBytes = 8 + 8 + 8 + 8 + 8;

// One waveform: a run of samples at one rate.
struct AnalogWaveform {
    double begin = 0, rate = 0;
    std::uint64_t downsample = 0, count = 0;
};

struct AnalogFile {
    std::string path;
    std::FILE* f = nullptr;
    int version = 0;
    AnalogWaveform first;                    // every waveform shares its rate and downsample
    std::uint64_t waveforms = 1, total = 0;  // waveforms and samples in the file
    std::uint64_t layout = 0;                // a hash of the waveforms' begins and lengths
};

InputError failIn(const std::string& path, const std::string& what) {
    return InputError(fmt::format("{}: {}", path, what));
}

template <typename T>
T field(const unsigned char* p) {
    T v;
    std::memcpy(&v, p, sizeof v);
    return v;
}

// A version 1 waveform header; false at the end of the file.
bool readWaveform(std::FILE* f, AnalogWaveform& w) {
    unsigned char h[kV1WaveformHeaderBytes];
    if (std::fread(h, 1, sizeof h, f) != sizeof h) return false;
    w.begin = field<double>(h);
    w.rate = field<double>(h + 16);
    w.downsample = std::uint64_t(field<std::int64_t>(h + 24));
    w.count = field<std::uint64_t>(h + 32);
    return true;
}

std::string makesNoCapture(const AnalogWaveform& w) {
    if (std::isfinite(w.begin) && w.rate > 0 && w.rate <= 1e12 && w.downsample > 0 &&
        w.downsample < (std::uint64_t(1) << 40))
        return {};
    return fmt::format("begin {} s, sample rate {}, downsample {} make no capture", w.begin, w.rate,
                       std::int64_t(w.downsample));
}

// Walks a version 1 file's waveforms: each fits in the file, at the first one's rate.
void walkWaveforms(AnalogFile& a, std::uint64_t size) {
    unsigned char n[8];
    if (std::fread(n, 1, 8, a.f) != 8) throw failIn(a.path, "ends inside its header (truncated)");
    a.waveforms = field<std::uint64_t>(n);
    std::uint64_t at = kCommonHeaderBytes + 8;
    for (std::uint64_t i = 0; i < a.waveforms; ++i) {
        AnalogWaveform w;
        if (!readWaveform(a.f, w))
            throw failIn(a.path, fmt::format("waveform {} of {} at byte {}: the file ends first "
                                             "(truncated)",
                                             i, a.waveforms, at));
        if (const std::string bad = makesNoCapture(w); !bad.empty())
            throw failIn(a.path, fmt::format("waveform {} at byte {}: {}", i, at, bad));
        if (i == 0) a.first = w;
        if (w.rate != a.first.rate || w.downsample != a.first.downsample)
            throw failIn(
                a.path, fmt::format("waveform {} at byte {}: sample rate {} / {} where "
                                    "waveform 0 has {} / {} (one rate is read)",
                                    i, at, w.rate, w.downsample, a.first.rate, a.first.downsample));
        at += kV1WaveformHeaderBytes;
        if (w.count > (size - at) / 4)
            throw failIn(a.path,
                         fmt::format("waveform {} at byte {} says {} samples, the file "
                                     "holds {} (truncated)",
                                     i, at - kV1WaveformHeaderBytes, w.count, (size - at) / 4));
        at += 4 * w.count;
        a.total += w.count;
        std::uint64_t begin_bits;
        std::memcpy(&begin_bits, &w.begin, 8);
        a.layout = (a.layout ^ begin_bits ^ (w.count << 1)) * 0x100000001b3ULL;
        if (std::fseek(a.f, long(at), SEEK_SET) != 0)
            throw failIn(a.path, fmt::format("cannot seek to byte {}", at));
    }
    if (at != size)
        throw failIn(a.path, fmt::format("{} bytes after the last waveform", size - at));
    if (a.waveforms == 0) a.first = {0, 1, 1, 0};
    std::fseek(a.f, kCommonHeaderBytes + 8, SEEK_SET);
}

void readVersion0(AnalogFile& a, std::uint64_t size) {
    unsigned char h[kV0HeaderBytes - kCommonHeaderBytes];
    if (std::fread(h, 1, sizeof h, a.f) != sizeof h)
        throw failIn(a.path, "ends inside its analog header (truncated)");
    a.first = {field<double>(h), double(field<std::uint64_t>(h + 8)), field<std::uint64_t>(h + 16),
               field<std::uint64_t>(h + 24)};
    if (const std::string bad = makesNoCapture(a.first); !bad.empty()) throw failIn(a.path, bad);
    const std::uint64_t held = (size - kV0HeaderBytes) / 4;
    if (held < a.first.count)
        throw failIn(a.path, fmt::format("says {} samples, the file holds {} (truncated)",
                                         a.first.count, held));
    if (size != kV0HeaderBytes + 4 * a.first.count)
        throw failIn(a.path, fmt::format("{} bytes after the last sample",
                                         size - kV0HeaderBytes - 4 * a.first.count));
    a.total = a.first.count;
    a.layout = a.first.count;
}

// Opens `path` and reads its header; the file's size must be that of its samples.
AnalogFile openAnalogFile(const std::string& path) {
    AnalogFile a;
    a.path = path;
    a.f = std::fopen(path.c_str(), "rb");
    if (!a.f) throw failIn(path, fmt::format("cannot open: {}", std::strerror(errno)));
    try {
        unsigned char h[kCommonHeaderBytes];
        const std::size_t got = std::fread(h, 1, sizeof h, a.f);
        if (got < sizeof h || std::memcmp(h, "<SALEAE>", 8) != 0)
            throw failIn(path, "not a Saleae binary export (no <SALEAE> identifier)");
        a.version = field<std::int32_t>(h + 8);
        const auto type = field<std::int32_t>(h + 12);
        if (type != 1)
            throw failIn(path, fmt::format("type {} where an analog channel (type 1) was "
                                           "expected",
                                           type));
        if (a.version != 0 && a.version != 1)
            throw failIn(path, fmt::format("Saleae analog export version {} is not read "
                                           "(versions 0 and 1 are)",
                                           a.version));
        std::fseek(a.f, 0, SEEK_END);
        const auto size = std::uint64_t(std::ftell(a.f));
        std::fseek(a.f, kCommonHeaderBytes, SEEK_SET);
        if (a.version == 0)
            readVersion0(a, size);
        else
            walkWaveforms(a, size);
    } catch (...) {
        std::fclose(a.f);
        throw;
    }
    return a;
}

class SaleaeAnalogSamples : public SampleSource {
public:
    SaleaeAnalogSamples(std::string name, std::vector<AnalogFile> files,
                        std::vector<AnalogChannel> channels)
        : name_(std::move(name)), files_(std::move(files)), channels_(std::move(channels)) {
        const AnalogFile& a = files_[0];
        period_ = double(a.first.downsample) / a.first.rate;
        wave_ = a.first;
        if (a.version == 1) {  // each waveform's header comes before its samples
            wave_.count = 0;
            waves_left_ = a.waveforms;
        }
    }
    ~SaleaeAnalogSamples() override {
        for (auto& f : files_)
            std::fclose(f.f);
    }
    const std::vector<AnalogChannel>& channels() const override { return channels_; }
    std::size_t slots() const override { return channels_.size(); }
    std::string formatName() const override { return "saleae-bin-analog"; }
    std::string fileName() const override { return name_; }
    double period() const override { return period_; }
    std::uint64_t bytesRead() const override { return 4 * sample_ * files_.size(); }
    std::uint64_t bytesTotal() const override { return 4 * files_[0].total * files_.size(); }
    [[noreturn]] void fail(const std::string& what) const override {
        throw InputError(fmt::format("{}: sample {}: {}", name_, sample_, what));
    }
    bool next(double& t, float* values) override {
        while (in_wave_ == wave_.count) {  // the next waveform, alike in every file
            if (waves_left_ == 0) return false;
            for (const AnalogFile& f : files_)
                if (!readWaveform(f.f, wave_)) fail(fmt::format("cannot read {}", f.path));
            --waves_left_;
            in_wave_ = 0;
        }
        for (std::size_t c = 0; c < files_.size(); ++c)
            if (std::fread(&values[c], 4, 1, files_[c].f) != 1)
                fail(fmt::format("cannot read {}", files_[c].path));
        t = wave_.begin + double(in_wave_++) * period_;
        ++sample_;
        return true;
    }

private:
    std::string name_;
    std::vector<AnalogFile> files_;
    std::vector<AnalogChannel> channels_;
    double period_ = 0;
    AnalogWaveform wave_;
    std::uint64_t waves_left_ = 0, in_wave_ = 0, sample_ = 0;
};

}  // namespace

std::unique_ptr<CaptureReader> openSaleaeAnalog(
    const std::string& name, const std::vector<std::pair<std::string, std::string>>& files,
    const OpenOptions& opts) {
    std::vector<AnalogFile> opened;
    std::vector<AnalogChannel> channels;
    try {
        for (const auto& [path, channel] : files) {
            opened.push_back(openAnalogFile(path));
            channels.push_back({channel, channel, channels.size(), -1});
            const AnalogFile& f = opened.back();
            const AnalogFile& a = opened[0];
            if (f.version != a.version || f.first.begin != a.first.begin ||
                f.first.rate != a.first.rate || f.first.downsample != a.first.downsample ||
                f.waveforms != a.waveforms || f.total != a.total || f.layout != a.layout)
                throw failIn(name, fmt::format("{} and {} differ in version, begin, sample rate, "
                                               "downsample, waveforms or length",
                                               a.path, f.path));
        }
    } catch (...) {
        for (auto& f : opened)
            std::fclose(f.f);
        throw;
    }
    return analogReader(
        std::make_unique<SaleaeAnalogSamples>(name, std::move(opened), std::move(channels)), opts);
}

}  // namespace busdecode
