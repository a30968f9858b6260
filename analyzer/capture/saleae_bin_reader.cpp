// Saleae Logic 2 binary export, digital channels (Saleae's "Binary Export Format"):
// one file per channel, `digital_N.bin`: "<SALEAE>", int32 version, int32 type (0 =
// digital), then
//   version 0: u32 initial state, f64 begin, f64 end, u64 n, f64 transition times[n]
//   version 1: u64 chunks, per chunk { u32 initial state, f64 sample rate, f64 begin,
//              f64 end, u64 n, f64 times[n] } (gaps between chunks hold no data)
// all little-endian, times in seconds. A folder of such files, or one of them, is one
// capture; the channels' transitions are merged in time order, each file read as a
// stream. Ticks count from the earliest begin: at version 1's common sample rate, else
// in nanoseconds. Analog files (type 1) go to saleae_analog_samples.cpp.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include <fmt/format.h>

#include "core/options.h"
#include "readers.h"

namespace busdecode {

namespace {

struct Chunk {
    bool version0 = false;
    std::uint32_t initial = 0;
    double rate = 0, begin = 0, end = 0;
    std::uint64_t count = 0;
    long offset = 0;  // of its first time
};

// One channel's file: its chunks checked at open, then its transitions one by one.
class SaleaeChannel {
public:
    SaleaeChannel(const std::string& path) : path_(path), f_(std::fopen(path.c_str(), "rb")) {
        if (!f_) throw fail(fmt::format("cannot open: {}", std::strerror(errno)));
        std::fseek(f_, 0, SEEK_END);
        size_ = std::uint64_t(std::ftell(f_));
        std::fseek(f_, 0, SEEK_SET);
        char magic[8];
        if (!read(magic, 8) || std::memcmp(magic, "<SALEAE>", 8) != 0)
            throw fail("not a Saleae binary export (no <SALEAE> identifier)");
        const std::int32_t version = get<std::int32_t>("header"),
                           type = get<std::int32_t>("header");
        if (version != 0 && version != 1)
            throw fail(fmt::format(
                "Saleae binary export version {} is not read (versions 0 and 1 are)", version));
        if (type == 1)
            throw fail(
                "an analog channel (type 1) among digital ones: decode the analog "
                "files in a folder of their own");
        if (type != 0) throw fail(fmt::format("type {} is not a Saleae export type", type));
        if (version == 0) {
            chunks_.push_back(chunkHeader(false));
        } else {
            const auto n = get<std::uint64_t>("header");
            for (std::uint64_t i = 0; i < n; ++i)
                chunks_.push_back(chunkHeader(true));
        }
        if (std::uint64_t(std::ftell(f_)) != size_)
            throw fail(fmt::format("{} bytes after the last transition (not a Saleae export?)",
                                   size_ - std::uint64_t(std::ftell(f_))));
    }
    ~SaleaeChannel() {
        if (f_) std::fclose(f_);
    }
    SaleaeChannel(const SaleaeChannel&) = delete;
    SaleaeChannel& operator=(const SaleaeChannel&) = delete;

    double begin() const { return chunks_.empty() ? 0 : chunks_.front().begin; }
    double end() const { return chunks_.empty() ? 0 : chunks_.back().end; }
    double rate() const { return chunks_.empty() || chunks_[0].version0 ? 0 : chunks_[0].rate; }
    bool sameRate(double r) const {
        for (const auto& c : chunks_)
            if (c.version0 || c.rate != r) return false;
        return true;
    }
    std::uint8_t initial() const {
        return chunks_.empty() ? 0 : std::uint8_t(chunks_[0].initial & 1);
    }

    // The next change: its time (seconds) and the level after it. False at the end.
    bool next(double& t, std::uint8_t& level) {
        while (chunk_ < chunks_.size()) {
            Chunk& c = chunks_[chunk_];
            if (!chunk_started_) {
                chunk_started_ = true;
                std::fseek(f_, c.offset, SEEK_SET);
                taken_ = 0;
                if (chunk_ > 0 && !(c.begin >= last_))
                    throw fail(
                        fmt::format("chunk {} begins at {} s, before the chunk before it ends",
                                    chunk_, c.begin));
                if (chunk_ > 0 && std::uint8_t(c.initial & 1) != level_) {
                    t = last_ = c.begin;
                    level = level_ = std::uint8_t(c.initial & 1);
                    return true;
                }
                level_ = std::uint8_t(c.initial & 1);
            }
            if (taken_ < c.count) {
                t = get<double>(fmt::format("transition {}", taken_));
                if (!(t >= last_))
                    throw fail(fmt::format("transition {} at {} s is before the one before it",
                                           taken_, t));
                last_ = t;
                ++taken_;
                level = level_ = std::uint8_t(level_ ^ 1);
                return true;
            }
            ++chunk_;
            chunk_started_ = false;
        }
        return false;
    }
    std::uint64_t bytesRead() const { return f_ ? std::uint64_t(std::ftell(f_)) : 0; }
    std::uint64_t bytesTotal() const { return size_; }

private:
    InputError fail(const std::string& what) const {
        return InputError(fmt::format("{}: {}", path_, what));
    }
    bool read(void* out, std::size_t n) { return std::fread(out, 1, n, f_) == n; }
    template <class T>
    T get(const std::string& what) {
        T v;
        if (!read(&v, sizeof v)) throw fail(fmt::format("ends inside its {} (truncated)", what));
        return v;
    }
    Chunk chunkHeader(bool v1) {
        Chunk c;
        c.version0 = !v1;
        const std::string what = fmt::format("chunk {} header", chunks_.size());
        c.initial = get<std::uint32_t>(what);
        if (v1) c.rate = get<double>(what);
        c.begin = get<double>(what);
        c.end = get<double>(what);
        c.count = get<std::uint64_t>(what);
        c.offset = std::ftell(f_);
        if (!std::isfinite(c.begin) || !std::isfinite(c.end) || c.end < c.begin ||
            (v1 && !(c.rate > 0 && std::isfinite(c.rate))))
            throw fail(fmt::format("{}: begin {} s, end {} s, rate {} make no capture", what,
                                   c.begin, c.end, c.rate));
        if (c.count > (size_ - std::uint64_t(c.offset)) / 8)
            throw fail(fmt::format("{} says {} transitions, the file holds {} (truncated)", what,
                                   c.count, (size_ - std::uint64_t(c.offset)) / 8));
        std::fseek(f_, long(c.offset + long(c.count * 8)), SEEK_SET);
        return c;
    }

    std::string path_;
    std::FILE* f_;
    std::uint64_t size_ = 0;
    std::vector<Chunk> chunks_;
    std::size_t chunk_ = 0;
    bool chunk_started_ = false;
    std::uint64_t taken_ = 0;
    std::uint8_t level_ = 0;
    double last_ = -INFINITY;
};

// The export's type field (0 digital, 1 analog), or -1 when the file is shorter.
int saleaeTypeOf(const std::string& path) {
    std::int32_t type = -1;
    if (std::FILE* f = std::fopen(path.c_str(), "rb")) {
        if (std::fseek(f, 12, SEEK_SET) != 0 || std::fread(&type, 4, 1, f) != 1) type = -1;
        std::fclose(f);
    }
    return type;
}

class SaleaeBinReader : public CaptureReader {
public:
    SaleaeBinReader(std::string name, const std::vector<std::pair<std::string, std::string>>& files)
        : name_(std::move(name)) {
        for (const auto& [path, name] : files) {
            channels_.push_back(std::make_unique<SaleaeChannel>(path));
            signals_.push_back({name, std::filesystem::path(path).stem().string(), 1});
            (void)path;
        }
        begin_ = channels_[0]->begin();
        double end = channels_[0]->end();
        for (const auto& c : channels_) {
            begin_ = std::min(begin_, c->begin());
            end = std::max(end, c->end());
        }
        const double r = channels_[0]->rate();
        bool same = r > 0 && r == std::floor(r) && r < 1e13;
        for (const auto& c : channels_)
            same = same && c->sameRate(r);
        per_second_ = same ? r : 1e9;
        end_ = ticks(end);
    }

    const std::vector<SignalInfo>& signals() const override { return signals_; }
    Timebase timebase() const override { return Timebase{1, std::int64_t(per_second_)}; }
    std::string formatName() const override { return "saleae-bin"; }
    bool changesOnly() const override { return true; }
    std::uint64_t bytesRead() const override {
        std::uint64_t n = 0;
        for (const auto& c : channels_)
            n += c->bytesRead();
        return n;
    }
    std::uint64_t bytesTotal() const override {
        std::uint64_t n = 0;
        for (const auto& c : channels_)
            n += c->bytesTotal();
        return n;
    }

    void select(const std::vector<LineRef>& lines) override {
        checkSelection(lines);
        sel_.clear();
        for (const auto& l : lines) {
            if (l.signal < 0 || l.signal >= int(channels_.size()))
                throw std::out_of_range("SaleaeBinReader::select");
            sel_.push_back({std::size_t(l.signal), 0, 0, false});
        }
    }
    std::vector<std::uint8_t> initialLevels() override {
        std::vector<std::uint8_t> out;
        for (auto& s : sel_) {
            out.push_back(channels_[s.channel]->initial());
            advance(s);
        }
        return out;
    }
    Tick startTick() const override { return 0; }
    Tick endTick() const override { return end_; }

    bool next(EdgeBlock& block) override {
        block.clear();
        while (block.edges.size() < kEdgeBlockSize) {
            std::size_t best = sel_.size();
            for (std::size_t i = 0; i < sel_.size(); ++i)
                if (sel_[i].pending && (best == sel_.size() || sel_[i].t < sel_[best].t)) best = i;
            if (best == sel_.size()) break;
            block.edges.push_back(Edge(sel_[best].t, std::uint32_t(best), sel_[best].level));
            end_ = std::max(end_, sel_[best].t);  // a transition past the stated end
            advance(sel_[best]);
        }
        block.known_until = block.edges.empty() ? end_ : block.edges.back().t;
        return !block.edges.empty();
    }

private:
    struct Sel {
        std::size_t channel;
        Tick t;
        std::uint8_t level;
        bool pending;
    };
    Tick ticks(double seconds) const {
        const double x = std::round((seconds - begin_) * per_second_);
        if (!(x >= 0 && x < double(kMaxEdgeTick)))
            throw InputError(fmt::format("{}: a time of {} s is out of range", name_, seconds));
        return Tick(x);
    }
    void advance(Sel& s) {
        double t;
        s.pending = channels_[s.channel]->next(t, s.level);
        if (s.pending) s.t = ticks(t);
    }

    std::string name_;
    std::vector<std::unique_ptr<SaleaeChannel>> channels_;
    std::vector<SignalInfo> signals_;
    std::vector<Sel> sel_;
    double begin_ = 0, per_second_ = 1e9;
    Tick end_ = 0;
};

}  // namespace

std::unique_ptr<CaptureReader> openSaleaeBin(const std::string& path, const OpenOptions& opts) {
    namespace fs = std::filesystem;
    using Files = std::vector<std::pair<std::string, std::string>>;  // path, signal name
    auto byIndex = [](Files& files) {
        std::sort(files.begin(), files.end(), [](const auto& a, const auto& b) {
            return a.second.size() != b.second.size() ? a.second.size() < b.second.size()
                                                      : a.second < b.second;
        });
    };
    if (fs::is_directory(path)) {
        Files digital, analog;
        for (const auto& e : fs::directory_iterator(path)) {
            const std::string stem = e.path().stem().string();
            if (e.path().extension() != ".bin") continue;
            if (stem.rfind("digital_", 0) == 0)
                digital.push_back({e.path().string(), stem.substr(8)});
            if (stem.rfind("analog_", 0) == 0) analog.push_back({e.path().string(), stem});
        }
        byIndex(digital);
        byIndex(analog);
        if (!digital.empty()) return std::make_unique<SaleaeBinReader>(path, digital);
        if (!analog.empty()) return openSaleaeAnalog(path, analog, opts);
        throw InputError(fmt::format(
            "{}: is a directory without Saleae digital_N.bin or analog_N.bin files", path));
    }
    const std::string stem = fs::path(path).stem().string();
    if (saleaeTypeOf(path) == 1) return openSaleaeAnalog(path, {{path, stem}}, opts);
    return std::make_unique<SaleaeBinReader>(
        path, Files{{path, stem.rfind("digital_", 0) == 0 ? stem.substr(8) : stem}});
}

}  // namespace busdecode
