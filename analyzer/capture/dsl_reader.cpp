// DSView session (.dsl) reader: a ZIP holding `header` (INI: rate, samples, blocks, probe
// names by hardware index) and, per saved probe, bit-planes `L-<probe>/<block>`: 2^24
// samples a block, sample k in bit k % 8 of byte k / 8 (LSB first); every block but the
// last is full. Only the selected probes' planes are read, a window at a time, so memory
// stays flat; edges are where a plane's bit differs from the one before it. One tick is
// one sample. DSO (`O-<ch>/0`) and analog (`A-0/<block>`) sessions hold voltages: they go
// to dsl_reader_analog.cpp.
#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstring>
#include <map>

#include <fmt/format.h>

#include "core/options.h"
#include "dsl_reader_header.h"
#include "readers.h"
#include "session_ini.h"
#include "wall_clock.h"
#include "zip_archive.h"

namespace busdecode {

namespace {

constexpr std::uint64_t kBlockSamples = std::uint64_t(1) << 24;
constexpr std::uint64_t kBlockBytes = kBlockSamples / 8;
constexpr std::size_t kWindowBytes = 64 << 10;  // per selected probe

std::uint64_t number(const std::string& file, const std::string& key, const std::string& text) {
    if (text.empty() || text.find_first_not_of("0123456789") != std::string::npos ||
        text.size() > 18)
        throw InputError(
            fmt::format("{}: header: {} = '{}' is not a count", file, key, printable(text)));
    return std::stoull(text);
}

// Metadata, never a reason to refuse the file: false when `text` is not a whole number.
bool parseTime(const std::string& text, std::int64_t& out) {
    const char* end = text.data() + text.size();
    const auto [p, ec] = std::from_chars(text.data(), end, out);
    return ec == std::errc() && p == end;
}

DslHeader parseHeader(const std::string& file, const std::string& text) {
    DslHeader h;
    std::string rate_text;
    bool have_rate = false, have_samples = false, have_blocks = false, have_trigger = false;
    std::int64_t trigger_ms = 0;
    std::uint64_t trigger_pos = 0;
    forEachIniLine(text, [&](const IniLine& l) {
        if (l.indented) {  // a DSO/analog probe's settings
            if (l.has_value) h.probe_settings[std::string(l.key)] = std::string(l.value);
            return;
        }
        if (!l.has_value)
            throw InputError(fmt::format("{}: header line {}: '{}' is not key = value", file,
                                         l.number, printable(l.key)));
        const std::string key(l.key), value(l.value);
        if (l.section == "[version]" && key == "version") {
            h.version = int(number(file, key, value));
        } else if (l.section != "[header]") {
            return;
        } else if (key == "bits") {
            h.bits = int(number(file, key, value));
        } else if (key == "device mode") {
            h.mode = int(number(file, key, value));
        } else if (key == "total samples") {
            h.samples = number(file, key, value);
            have_samples = true;
        } else if (key == "total blocks") {
            h.blocks = number(file, key, value);
            have_blocks = true;
        } else if (key == "samplerate") {
            rate_text = value;
            h.rate = parseRateHz(value);
            have_rate = true;
        } else if (key == "trigger time") {
            have_trigger = parseTime(value, trigger_ms);
        } else if (key == "trigger pos") {
            std::int64_t pos = 0;
            if (parseTime(value, pos) && pos > 0) trigger_pos = std::uint64_t(pos);
        } else if (key.rfind("probe", 0) == 0 && key.size() > 5 &&
                   key.find_first_not_of("0123456789", 5) == std::string::npos) {
            h.probes[int(number(file, key, key.substr(5)))] = value;
        }
    });
    auto missing = [&](const char* what) {
        return InputError(fmt::format("{}: header has no {} (not a DSView session?)", file, what));
    };
    if (!have_samples) throw missing("'total samples'");
    if (!have_blocks) throw missing("'total blocks'");
    if (!have_rate) throw missing("samplerate");
    if (h.rate <= 0)
        throw InputError(
            fmt::format("{}: header: samplerate '{}' is not a rate", file, printable(rate_text)));
    if (h.probes.empty()) throw missing("probes");
    // The trigger's instant (ms since 1970), `trigger pos` samples into the capture. A
    // session never triggered says its local midnight of 1 January 1970 (-28800000 in
    // DSView's demo): no time.
    constexpr double kUnsetBefore = 2 * 86400000.0, kAfterAnyDate = 1e15;
    const double start_ms = double(trigger_ms) - double(trigger_pos) * 1e3 / double(h.rate);
    if (have_trigger && trigger_ms > kUnsetBefore && start_ms > kUnsetBefore &&
        start_ms < kAfterAnyDate)
        h.wall_clock = wallClockFromUnixMs(std::llround(start_ms));
    return h;
}

class DslReader : public CaptureReader {
public:
    DslReader(std::unique_ptr<ZipArchive> zip, const DslHeader& header, const OpenOptions& opts)
        : zip_(std::move(zip)), opts_(opts) {
        const std::string& file = zip_->name();
        const DslHeader& h = header;
        checkMode(h);
        samples_ = h.samples;
        wall_clock_ = h.wall_clock;
        rate_ = h.rate;
        const std::uint64_t need = (samples_ + kBlockSamples - 1) / kBlockSamples;
        if (h.blocks != need)
            throw InputError(
                fmt::format("{}: header: total blocks = {}, but {} samples take {} blocks of 2^24",
                            file, h.blocks, samples_, need));
        blocks_ = h.blocks;
        if (auto decoders = zip_->readText("decoders")) noteDecoders(*decoders);
        for (const auto& [index, name] : h.probes) {
            probes_.push_back(index);
            signals_.push_back({name, name, 1});
            checkBlocks(index);
        }
    }

    const std::vector<SignalInfo>& signals() const override { return signals_; }
    Timebase timebase() const override { return Timebase::fromSampleRate(rate_); }
    std::string formatName() const override { return "dsview-dsl"; }
    std::string wallClockStart() const override { return wall_clock_; }
    std::uint64_t bytesRead() const override { return bytes_read_; }
    std::uint64_t bytesTotal() const override { return bytes_total_; }
    bool changesOnly() const override { return true; }
    std::vector<std::string> notes() const override { return notes_; }

    void select(const std::vector<LineRef>& lines) override {
        checkSelection(lines);
        lines_.clear();
        for (const auto& l : lines) {
            if (l.signal < 0 || l.signal >= int(probes_.size()))
                throw std::out_of_range("DslReader::select");
            lines_.push_back({probes_[std::size_t(l.signal)], {}, nullptr, 0});
        }
        changes_.assign(lines_.size(), 0);
        words_at_.assign(lines_.size(), 0);
        bytes_total_ = 0;
        for (std::uint64_t b = 0; b < blocks_; ++b)
            bytes_total_ += blockBytes(b) * lines_.size();
    }

    std::vector<std::uint8_t> initialLevels() override {
        if (!started_) {
            started_ = true;
            if (samples_ > 0 && !lines_.empty()) {
                loadWindow();
                for (auto& l : lines_)
                    l.prev = l.plane[0] & 1;
            }
        }
        std::vector<std::uint8_t> out;
        for (const auto& l : lines_)
            out.push_back(std::uint8_t(l.prev));
        return out;
    }
    Tick startTick() const override { return 0; }
    Tick endTick() const override { return samples_ > 0 ? Tick(samples_ - 1) : 0; }

    bool next(EdgeBlock& block) override {
        block.clear();
        if (!started_) initialLevels();
        if (lines_.empty() || done_) return false;
        block.edges.resize(kEdgeBlockSize);
        Edge* out = block.edges.data();
        Edge* const room = out + kEdgeBlockSize - 64 * lines_.size();  // a whole word's edges
        while (out <= room) {
            if (word_ == words_ && !loadWindow()) {
                done_ = true;
                break;
            }
            out = scanWords(out, room);
        }
        block.edges.resize(std::size_t(out - block.edges.data()));
        block.known_until = done_ ? endTick() : Tick(window_start_ + word_ * 64) - 1;
        return !done_ || !block.edges.empty();
    }

private:
    struct Line {
        int probe;
        std::vector<std::uint64_t> plane;  // the window's words
        std::unique_ptr<ZipMember> member;
        std::uint64_t prev;  // the last sample's level
    };

    void checkMode(const DslHeader& h) const {
        const std::string& file = zip_->name();
        if (h.mode != 0)
            throw InputError(
                fmt::format("{}: header: device mode {} is not a DSView mode", file, h.mode));
        if (h.version < 2)
            throw InputError(fmt::format(
                "{}: DSView session version {} (one `data` member) is not read: version 2 "
                "and 3 sessions (`L-<probe>/<block>` members) are",
                file, h.version));
    }

    // The `decoders` member (JSON) on one line, whitespace folded, so it can be copied.
    void noteDecoders(const std::string& json) {
        std::string folded;
        bool in_string = false;
        for (char ch : json) {
            if (ch == '"') in_string = !in_string;
            const bool space = ch == ' ' || ch == '\n' || ch == '\r' || ch == '\t';
            if (space && !in_string) {
                if (!folded.empty() && folded.back() != ' ' && folded.back() != '[' &&
                    folded.back() != '{')
                    folded += ' ';
                continue;
            }
            if ((ch == ']' || ch == '}') && !folded.empty() && folded.back() == ' ')
                folded.pop_back();
            folded += ch;
        }
        while (!folded.empty() && folded.back() == ' ')
            folded.pop_back();
        if (folded != "[]" && !folded.empty())
            notes_.push_back("DSView decoders: " + printable(folded, 4000));
    }

    // Bytes a block holds: every block but the last is full; the last holds the rest,
    // rounded up to whole 64-sample words.
    std::uint64_t blockBytes(std::uint64_t b) const {
        if (b + 1 < blocks_) return kBlockBytes;
        const std::uint64_t rest = samples_ - b * kBlockSamples;
        return (rest + 63) / 64 * 8;
    }

    static std::string memberName(int probe, std::uint64_t block) {
        return fmt::format("L-{}/{}", probe, block);
    }

    void checkBlocks(int probe) {
        for (std::uint64_t b = 0; b < blocks_; ++b) {
            const std::string m = memberName(probe, b);
            const auto size = zip_->size(m);
            if (!size) throw InputError(fmt::format("{}: block {} is missing", zip_->name(), m));
            const std::uint64_t want = blockBytes(b);
            const bool last = b + 1 == blocks_;
            // DSView may round the last block up further (to its 64-sample save units).
            if (last ? (*size < (samples_ - b * kBlockSamples + 7) / 8 || *size > kBlockBytes)
                     : *size != want)
                throw InputError(fmt::format(
                    "{}: block {} holds {} bytes, {} {} (wrong block size)", zip_->name(), m, *size,
                    last ? "the last block of these samples holds" : "a full block holds", want));
        }
    }

    // Reads the next window of every selected plane; false at the end of the samples.
    bool loadWindow() {
        window_start_ += window_samples_;
        if (window_start_ >= samples_) return false;
        const std::uint64_t block = window_start_ / kBlockSamples;
        const std::uint64_t block_end = std::min(samples_, (block + 1) * kBlockSamples);
        const std::size_t bytes =
            std::size_t(std::min<std::uint64_t>(kWindowBytes, (block_end - window_start_ + 7) / 8));
        for (auto& l : lines_) {
            if (window_start_ % kBlockSamples == 0)
                l.member = std::make_unique<ZipMember>(*zip_, memberName(l.probe, block));
            l.plane.assign((bytes + 7) / 8, 0);
            l.member->readExactly(l.plane.data(), bytes);
            bytes_read_ += bytes;
        }
        window_samples_ = std::uint64_t(bytes) * 8;
        // Bits past the last sample are not samples: the last word's are masked off.
        const std::uint64_t end = std::min(samples_ - window_start_, window_samples_);
        words_ = std::size_t((end + 63) / 64);
        word_ = 0;
        tail_mask_ = end % 64 ? (std::uint64_t(1) << (end % 64)) - 1 : ~std::uint64_t(0);
        return true;
    }

    // Edges of the window's words from word_ on, until `room` is passed; each word's
    // changes are handed out sample by sample, lines in selection order at a sample.
    Edge* scanWords(Edge* out, Edge* room) {
        const std::size_t n = lines_.size();
        std::uint64_t* const changes = changes_.data();
        std::uint64_t* const words = words_at_.data();
        for (; word_ < words_ && out <= room; ++word_) {
            const std::uint64_t valid = word_ + 1 == words_ ? tail_mask_ : ~std::uint64_t(0);
            std::uint64_t any = 0;
            for (std::size_t i = 0; i < n; ++i) {
                const std::uint64_t w = lines_[i].plane[word_];
                words[i] = w;
                changes[i] = (w ^ ((w << 1) | lines_[i].prev)) & valid;
                any |= changes[i];
                lines_[i].prev = w >> 63;
            }
            if (!any) continue;
            const Tick base = Tick(window_start_ + word_ * 64);
            for (; any; any &= any - 1) {
                const int b = std::countr_zero(any);
                for (std::size_t i = 0; i < n; ++i) {
                    *out = Edge(base + b, std::uint32_t(i), std::uint8_t((words[i] >> b) & 1));
                    out += (changes[i] >> b) & 1;
                }
            }
        }
        return out;
    }

    std::unique_ptr<ZipArchive> zip_;
    OpenOptions opts_;
    std::uint64_t samples_ = 0, blocks_ = 0;
    std::int64_t rate_ = 0;
    std::string wall_clock_;
    std::vector<int> probes_;
    std::vector<SignalInfo> signals_;
    std::vector<std::string> notes_;
    std::vector<Line> lines_;
    std::uint64_t window_start_ = 0;    // sample of the window's first word
    std::uint64_t window_samples_ = 0;  // its length (the next one starts there)
    std::size_t words_ = 0, word_ = 0;
    std::uint64_t tail_mask_ = ~std::uint64_t(0);
    std::vector<std::uint64_t> changes_, words_at_;  // per line, for the word being scanned
    std::uint64_t bytes_read_ = 0, bytes_total_ = 0;
    bool started_ = false, done_ = false;
};

}  // namespace

std::unique_ptr<CaptureReader> openDsl(std::unique_ptr<ZipArchive> zip, const OpenOptions& opts) {
    const DslHeader h = parseHeader(zip->name(), *zip->readText("header"));
    if (h.mode == 1 || h.mode == 2) return openDslAnalog(std::move(zip), h, opts);
    return std::make_unique<DslReader>(std::move(zip), h, opts);
}

}  // namespace busdecode
