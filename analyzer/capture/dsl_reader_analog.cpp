// DSView oscilloscope (device mode 1) and analog (device mode 2) sessions: 8-bit ADC codes
// as volts for the analog layer (analog_capture.h), which makes the edges:
// - DSO: one member per enabled channel, `O-<ch>/0`, a byte per sample; volts =
//   (vOffset - code) x vDiv (mV/div) x vFactor x 10 divisions / 255 codes (a higher code
//   is a lower voltage, as DSView draws it);
// - analog: `A-0/<block>`, the enabled channels interleaved sample by sample, blocks in
//   order; volts = (vOffset - code) x (mapMax - mapMin) / 255.
// Members are read a window at a time, so memory stays flat.
#include <cmath>
#include <cstring>
#include <vector>

#include <fmt/format.h>

#include "analog_capture.h"
#include "core/options.h"
#include "dsl_reader_header.h"

namespace busdecode {

namespace {

constexpr std::size_t kWindowRows = 16 << 10;
constexpr double kCodes = 255, kDivisions = 10;

struct DslChannel {
    int probe;
    double offset, volts_per_code;
};

double setting(const DslHeader& h, const std::string& file, const std::string& key,
               double fallback) {
    const auto it = h.probe_settings.find(key);
    if (it == h.probe_settings.end()) return fallback;
    char* end = nullptr;
    const double v = std::strtod(it->second.c_str(), &end);
    if (it->second.empty() || *end != '\0' || !std::isfinite(v))
        throw InputError(fmt::format("{}: header: {} = '{}' is not a number", file, key,
                                     it->second.substr(0, 40)));
    return v;
}

std::vector<DslChannel> channelsOf(const DslHeader& h, const std::string& file) {
    std::vector<DslChannel> out;
    for (const auto& [index, name] : h.probes) {
        const std::string i = std::to_string(index);
        if (setting(h, file, "enable" + i, 1) == 0) continue;
        const double offset = setting(h, file, "vOffset" + i, 128);
        double scale;
        if (h.mode == 1)
            scale = setting(h, file, "vDiv" + i, 1000) * 1e-3 * setting(h, file, "vFactor" + i, 1) *
                    kDivisions / kCodes;
        else
            scale =
                (setting(h, file, "mapMax" + i, 5) - setting(h, file, "mapMin" + i, -5)) / kCodes;
        if (!(scale > 0))
            throw InputError(fmt::format("{}: header: probe {} has no voltage scale", file, index));
        out.push_back({index, offset, scale});
    }
    if (out.empty()) throw InputError(fmt::format("{}: header: no enabled probe", file));
    return out;
}

class DslAnalogSamples : public SampleSource {
public:
    DslAnalogSamples(std::unique_ptr<ZipArchive> zip, const DslHeader& h)
        : zip_(std::move(zip)), mode_(h.mode), samples_(h.samples), blocks_(h.blocks) {
        const std::string& file = zip_->name();
        if (h.bits != 8)
            throw InputError(
                fmt::format("{}: header: bits = {}: only 8-bit samples are read", file, h.bits));
        if (h.version < 2)
            throw InputError(fmt::format("{}: DSView session version {} is not read (2 and 3 are)",
                                         file, h.version));
        probes_ = channelsOf(h, file);
        for (const DslChannel& c : probes_) {
            const std::string name = h.probes.at(c.probe);
            channels_.push_back({name, name, channels_.size(), -1});
        }
        period_ = 1.0 / double(h.rate);
        checkMembers();
    }
    const std::vector<AnalogChannel>& channels() const override { return channels_; }
    std::size_t slots() const override { return channels_.size(); }
    std::string formatName() const override {
        return mode_ == 1 ? "dsview-dsl-dso" : "dsview-dsl-analog";
    }
    std::string fileName() const override { return zip_->name(); }
    double period() const override { return period_; }
    std::uint64_t bytesRead() const override { return sample_ * probes_.size(); }
    std::uint64_t bytesTotal() const override { return samples_ * probes_.size(); }
    [[noreturn]] void fail(const std::string& what) const override {
        throw InputError(fmt::format("{}: sample {}: {}", zip_->name(), sample_, what));
    }
    bool next(double& t, float* values) override {
        if (sample_ == samples_) return false;
        if (at_ == rows_) loadWindow();
        for (std::size_t c = 0; c < probes_.size(); ++c) {
            const unsigned char code =
                mode_ == 1 ? window_[c][at_] : window_[0][at_ * probes_.size() + c];
            values[c] = float((probes_[c].offset - code) * probes_[c].volts_per_code);
        }
        ++at_;
        t = double(sample_++) * period_;
        return true;
    }

private:
    std::string member(std::size_t c, std::uint64_t block) const {
        return mode_ == 1 ? fmt::format("O-{}/0", probes_[c].probe) : fmt::format("A-0/{}", block);
    }

    // Every member there, its size whole rows, the rows adding up to `total samples`.
    void checkMembers() {
        const std::string& file = zip_->name();
        if (mode_ == 1) {
            if (blocks_ != 1)
                throw InputError(
                    fmt::format("{}: header: total blocks = {} in an oscilloscope "
                                "session, which holds one",
                                file, blocks_));
            for (std::size_t c = 0; c < probes_.size(); ++c) {
                const auto size = zip_->size(member(c, 0));
                if (!size)
                    throw InputError(fmt::format("{}: block {} is missing", file, member(c, 0)));
                if (*size != samples_)
                    throw InputError(
                        fmt::format("{}: block {} holds {} bytes, {} samples take {} "
                                    "(wrong block size)",
                                    file, member(c, 0), *size, samples_, samples_));
            }
            block_rows_.push_back(samples_);
            return;
        }
        std::uint64_t rows = 0;
        for (std::uint64_t b = 0; b < blocks_; ++b) {
            const auto size = zip_->size(member(0, b));
            if (!size) throw InputError(fmt::format("{}: block {} is missing", file, member(0, b)));
            if (*size % probes_.size() != 0 || *size == 0)
                throw InputError(
                    fmt::format("{}: block {} holds {} bytes, not whole rows of {} "
                                "channels (wrong block size)",
                                file, member(0, b), *size, probes_.size()));
            block_rows_.push_back(*size / probes_.size());
            rows += block_rows_.back();
        }
        if (rows != samples_)
            throw InputError(
                fmt::format("{}: the A-0 blocks hold {} samples, the header says "
                            "total samples = {} (wrong block size)",
                            file, rows, samples_));
    }

    void loadWindow() {
        if (block_left_ == 0) {  // the next block's members
            members_.clear();
            for (std::size_t c = 0; c < (mode_ == 1 ? probes_.size() : 1); ++c)
                members_.push_back(std::make_unique<ZipMember>(*zip_, member(c, block_)));
            block_left_ = block_rows_[std::size_t(block_++)];
        }
        rows_ = std::size_t(std::min<std::uint64_t>(kWindowRows, block_left_));
        block_left_ -= rows_;
        window_.resize(members_.size());
        const std::size_t per_row = mode_ == 1 ? 1 : probes_.size();
        for (std::size_t m = 0; m < members_.size(); ++m) {
            window_[m].resize(rows_ * per_row);
            members_[m]->readExactly(window_[m].data(), window_[m].size());
        }
        at_ = 0;
    }

    std::unique_ptr<ZipArchive> zip_;
    int mode_;
    std::uint64_t samples_, blocks_;
    std::vector<DslChannel> probes_;
    std::vector<AnalogChannel> channels_;
    double period_ = 0;
    std::vector<std::uint64_t> block_rows_;  // rows in each block (one per analog block)
    std::vector<std::unique_ptr<ZipMember>> members_;
    std::vector<std::vector<unsigned char>> window_;
    std::uint64_t block_ = 0, block_left_ = 0, sample_ = 0;
    std::size_t rows_ = 0, at_ = 0;
};

}  // namespace

std::unique_ptr<CaptureReader> openDslAnalog(std::unique_ptr<ZipArchive> zip, const DslHeader& h,
                                             const OpenOptions& opts) {
    return analogReader(std::make_unique<DslAnalogSamples>(std::move(zip), h), opts);
}

}  // namespace busdecode
