// Saleae Logic 2 binary export, analog channels (Saleae's "Binary Export Format", version
// 0): one file per channel, `analog_N.bin`: "<SALEAE>", int32 version 0, int32 type 1,
// f64 begin time (s), u64 sample rate, u64 downsample, u64 n, then n float32 volts, all
// little-endian; sample k at begin + k * downsample / rate. A folder of such files (or
// one of them) is one capture, its channels read side by side and turned into edges by
// the analog layer (analog_capture.h). Version 1's analog layout is refused: it could not
// be checked against a real export.
#include <cmath>
#include <cstdio>
#include <cstring>

#include <fmt/format.h>

#include "analog_capture.h"
#include "core/options.h"
#include "readers.h"

namespace busdecode {

namespace {

constexpr long kAnalogHeaderBytes = 8 + 4 + 4 + 8 + 8 + 8 + 8;

struct AnalogFile {
    std::string path;
    std::FILE* f = nullptr;
    double begin = 0;
    std::uint64_t rate = 0, downsample = 0, count = 0;
};

InputError failIn(const std::string& path, const std::string& what) {
    return InputError(fmt::format("{}: {}", path, what));
}

// Opens `path` and reads its header; the file's size must be that of its samples.
AnalogFile openAnalogFile(const std::string& path) {
    AnalogFile a;
    a.path = path;
    a.f = std::fopen(path.c_str(), "rb");
    if (!a.f) throw failIn(path, fmt::format("cannot open: {}", std::strerror(errno)));
    unsigned char h[kAnalogHeaderBytes];
    const std::size_t got = std::fread(h, 1, sizeof h, a.f);
    auto close = [&](const std::string& what) {
        std::fclose(a.f);
        return failIn(path, what);
    };
    if (got < 16 || std::memcmp(h, "<SALEAE>", 8) != 0)
        throw close("not a Saleae binary export (no <SALEAE> identifier)");
    std::int32_t version, type;
    std::memcpy(&version, h + 8, 4);
    std::memcpy(&type, h + 12, 4);
    if (type != 1)
        throw close(fmt::format("type {} where an analog channel (type 1) was expected", type));
    if (version != 0)
        throw close(
            fmt::format("Saleae analog export version {} is not read (version 0 is)", version));
    if (got < sizeof h) throw close("ends inside its analog header (truncated)");
    std::memcpy(&a.begin, h + 16, 8);
    std::memcpy(&a.rate, h + 24, 8);
    std::memcpy(&a.downsample, h + 32, 8);
    std::memcpy(&a.count, h + 40, 8);
    if (!std::isfinite(a.begin) || a.rate == 0 || a.downsample == 0 || a.rate > 1'000'000'000'000)
        throw close(fmt::format("begin {} s, sample rate {}, downsample {} make no capture",
                                a.begin, a.rate, a.downsample));
    std::fseek(a.f, 0, SEEK_END);
    const auto size = std::uint64_t(std::ftell(a.f));
    const std::uint64_t held = (size - kAnalogHeaderBytes) / 4;
    if (held < a.count || size != kAnalogHeaderBytes + 4 * a.count) {
        const std::string what =
            held < a.count
                ? fmt::format("says {} samples, the file holds {} (truncated)", a.count, held)
                : fmt::format("{} bytes after the last sample",
                              size - kAnalogHeaderBytes - 4 * a.count);
        throw close(what);
    }
    std::fseek(a.f, kAnalogHeaderBytes, SEEK_SET);
    return a;
}

class SaleaeAnalogSamples : public SampleSource {
public:
    SaleaeAnalogSamples(std::string name, std::vector<AnalogFile> files,
                        std::vector<AnalogChannel> channels)
        : name_(std::move(name)), files_(std::move(files)), channels_(std::move(channels)) {
        period_ = double(files_[0].downsample) / double(files_[0].rate);
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
    std::uint64_t bytesTotal() const override { return 4 * files_[0].count * files_.size(); }
    [[noreturn]] void fail(const std::string& what) const override {
        throw InputError(fmt::format("{}: sample {}: {}", name_, sample_, what));
    }
    bool next(double& t, float* values) override {
        if (sample_ == files_[0].count) return false;
        for (std::size_t c = 0; c < files_.size(); ++c)
            if (std::fread(&values[c], 4, 1, files_[c].f) != 1)
                fail(fmt::format("cannot read {}", files_[c].path));
        t = files_[0].begin + double(sample_++) * period_;
        return true;
    }

private:
    std::string name_;
    std::vector<AnalogFile> files_;
    std::vector<AnalogChannel> channels_;
    double period_ = 0;
    std::uint64_t sample_ = 0;
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
            if (f.begin != opened[0].begin || f.rate != opened[0].rate ||
                f.downsample != opened[0].downsample || f.count != opened[0].count)
                throw failIn(name, fmt::format("{} and {} differ in begin, sample rate, downsample "
                                               "or length",
                                               opened[0].path, f.path));
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
