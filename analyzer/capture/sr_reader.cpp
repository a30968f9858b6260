// sigrok session (.sr) reader: a ZIP holding `metadata` (INI) and the raw logic
// samples in chunks `logic-1-1`, `logic-1-2`, ... (old sessions: one `logic-1`), each a
// run of little-endian words of `unitsize` bytes (1 to 8: up to 64 probes, as on the
// 34-channel Sysclk LWLA); probe N is bit N-1 of a word.
// Chunks are streamed through a fixed buffer; only changes of the selected probes
// become edges. One tick is one sample (timebase 1/samplerate).
//
// The sample rate is taken as the file states it, even where it is known to be wrong
// (sigrok-dumps' spi/ad7920 claims 5 Hz): ticks stay sample indices either way, so
// sample-based comparisons hold; nanosecond times then follow the stated rate.
//
// signals() lists every probe bit 0 .. total probes-1, so the 0-based index of a signal
// is its bit in the sample word; unnamed (disabled) probes are called D<bit>.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <map>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <unistd.h>
#include <zip.h>

#include "core/options.h"
#include "core/own_cache_lines.h"
#include "core/sample_rate.h"
#include "readers.h"
#include "session_ini.h"
#include "zip_archive.h"

namespace busdecode {

namespace {

// In cache lines of its own: its state is written as it reads (own_cache_lines.h).
class alignas(kOwnLineBytes) SrReader : public CaptureReader {
public:
    SrReader(std::unique_ptr<ZipArchive> archive, const OpenOptions& opts)
        : name_(archive->name()),
          opts_(opts),
          archive_(std::move(archive)),
          zip_(archive_->handle()) {
        readMetadata();
        findChunks();
    }
    ~SrReader() override {
        if (file_) zip_fclose(file_);
    }

    const std::vector<SignalInfo>& signals() const override { return signals_; }
    Timebase timebase() const override { return tb_; }
    std::string formatName() const override { return "sigrok-sr"; }

    void select(const std::vector<LineRef>& lines) override {
        checkSelection(lines);
        sel_.clear();
        mask_ = 0;
        for (std::size_t i = 0; i < lines.size(); ++i) {
            const int bit = lines[i].signal;
            if (bit < 0 || bit >= int(signals_.size())) throw std::out_of_range("SrReader::select");
            sel_.push_back({bit, std::uint32_t(i)});
            mask_ |= std::uint64_t(1) << bit;
        }
    }

    std::vector<std::uint8_t> initialLevels() override {
        std::vector<std::uint8_t> out(sel_.size(), 0);
        if (!started_) {
            started_ = true;
            std::uint64_t w = 0;
            if (readWord(w)) {
                prev_ = w & mask_;
                sample_ = 1;
            } else {
                done_ = true;  // no samples at all
                sample_ = 1;
            }
        }
        for (std::size_t i = 0; i < sel_.size(); ++i)
            out[i] = std::uint8_t((prev_ >> sel_[i].bit) & 1);
        return out;
    }
    Tick startTick() const override { return 0; }

    // Aligned to a cache line: its hot loop ran 12 % slower where unrelated code in the
    // library moved it within its lines; aligned, its place
    // depends on its own code alone.
    [[gnu::aligned(64)]] bool next(EdgeBlock& block) override {
        block.clear();
        if (!started_) initialLevels();
        if (done_) return false;
        // Edges are written through a pointer into the block sized to its capacity (a
        // store per selected line and no branch on which changed), and the block is cut
        // back to what was written.
        block.edges.resize(kEdgeBlockSize);
        Edge* const first = block.edges.data();
        Edge* out = first;
        Edge* const full = first + (kEdgeBlockSize - sel_.size());  // room for one sample
        while (out <= full) {
            if (pos_ + unit_ > len_ && !refill()) {
                done_ = true;
                break;
            }
            // Scan whole words in the buffer; edges only where a selected bit changes.
            const std::uint8_t* p = buf_.data() + pos_;
            const std::size_t words = (len_ - pos_) / unit_;
            // Sample indices are ticks, and an Edge holds 2^55 of them: centuries of
            // decompression away, but a crafted session must not wrap them.
            if (sample_ + words > std::uint64_t(lastTickOf(tb_)))
                throw InputError(fmt::format(
                    "{}: more than {} samples, past 2^55 or what times in ns can hold at this "
                    "samplerate",
                    name_, lastTickOf(tb_)));
            std::size_t k = scanPacked(p, words, out, full);
            p += k * unit_;
            for (; k < words && out <= full; ++k, p += unit_) {
                const std::uint64_t w = wordAt(p) & mask_;
                if (w != prev_) {
                    out = addEdges(out, Tick(sample_ + k), w);
                    prev_ = w;
                }
            }
            pos_ += k * unit_;
            sample_ += k;
        }
        block.edges.resize(std::size_t(out - first));
        if (done_) {
            block.known_until = endTick();
            return !block.edges.empty();
        }
        block.known_until = Tick(sample_) - 1;
        return true;
    }
    Tick endTick() const override { return sample_ > 0 ? Tick(sample_) - 1 : 0; }
    std::uint64_t bytesRead() const override { return consumed_ + pos_; }
    std::uint64_t bytesTotal() const override { return total_bytes_; }
    bool changesOnly() const override { return true; }  // edges only where a bit changes

private:
    struct Sel {
        int bit;
        std::uint32_t line;
    };

    // The edges of sample word w (masked) at tick t, against prev_, written at out (room
    // for one per selected line) in the order of the selected lines, as a tie keeps
    // reader order. Returns the end of what it wrote.
    Edge* addEdges(Edge* out, Tick t, std::uint64_t w) const {
        const std::uint64_t diff = w ^ prev_;
        for (const auto& s : sel_) {
            *out = Edge(t, s.line, std::uint8_t((w >> s.bit) & 1));
            out += (diff >> s.bit) & 1;
        }
        return out;
    }

    // The bulk of a session, eight bytes at a time (unitsize 1, 2 or 4: a whole number of
    // samples per load): each load is compared with itself shifted one sample, the last
    // sample before it shifted in, so that a load without a change costs one compare. At
    // 100 MS/s most samples repeat the one before; a sample at a time, each was a
    // compare and a branch the traffic's data decides. Returns how many of the `words`
    // samples at p it took (it stops when fewer than 8 bytes are left, or when the block
    // could not take a whole load's edges); the caller's loop does the rest.
    std::size_t scanPacked(const std::uint8_t* p, std::size_t words, Edge*& out, Edge* full) {
        static_assert(std::endian::native == std::endian::little,
                      "a load's first sample must be its low bytes, as in the file");
        if (unit_ != 1 && unit_ != 2 && unit_ != 4) return 0;  // 3, 5-8: the sample loop
        const unsigned shift = unsigned(8 * unit_);            // bits per sample
        const unsigned log2_shift = unit_ == 1 ? 3 : unit_ == 2 ? 4 : 5;
        const std::size_t per_load = 8 / unit_;
        const std::uint64_t sample_bits = unit_ == 4 ? 0xFFFFFFFFULL : (1ULL << shift) - 1;
        std::uint64_t mask = 0;
        for (std::size_t i = 0; i < per_load; ++i)
            mask |= mask_ << (shift * i);
        Edge* const last = full - (per_load - 1) * sel_.size();  // room for a whole load
        std::size_t k = 0;
        for (; k + per_load <= words && out <= last; k += per_load) {
            std::uint64_t w;
            std::memcpy(&w, p + k * unit_, 8);
            w &= mask;
            std::uint64_t changed = w ^ ((w << shift) | prev_);
            while (changed) {
                const unsigned i = unsigned(std::countr_zero(changed)) >> log2_shift;
                const std::uint64_t s = (w >> (shift * i)) & sample_bits;
                out = addEdges(out, Tick(sample_ + k + i), s);
                prev_ = s;
                changed &= ~(sample_bits << (shift * i));
            }
        }
        return k;
    }

    // An entry of the ZIP opened for reading; one that is there but cannot be read says
    // why (sigrok writes Deflate; another tool's LZMA or zstd entry is not a missing one).
    zip_file_t* openEntry(const std::string& entry) {
        zip_stat_t st;
        if (zip_stat(zip_, entry.c_str(), 0, &st) != 0) return nullptr;
        if ((st.valid & ZIP_STAT_COMP_METHOD) &&
            !zip_compression_method_supported(st.comp_method, 0))
            throw InputError(fmt::format(
                "{}: entry {} is compressed with a method this build cannot read (ZIP method "
                "{}, {}); re-save the session with sigrok (Deflate)",
                name_, printable(entry), st.comp_method, methodName(st.comp_method)));
        zip_file_t* f = zip_fopen(zip_, entry.c_str(), 0);
        if (!f)
            throw InputError(fmt::format("{}: cannot read entry {}: {}", name_, printable(entry),
                                         zip_strerror(zip_)));
        return f;
    }
    static const char* methodName(std::int32_t m) {
        switch (m) {
            case ZIP_CM_BZIP2:
                return "bzip2";
            case 14:
                return "LZMA";  // ZIP_CM_LZMA
            case 93:
                return "zstd";  // ZIP_CM_ZSTD
            case 95:
                return "xz";  // ZIP_CM_XZ
            case 98:
                return "PPMd";
            default:
                return "unknown";
        }
    }

    void readMetadata() {
        zip_stat_t st;
        zip_file_t* f = openEntry("metadata");
        if (!f || zip_stat(zip_, "metadata", 0, &st) != 0)
            throw InputError(fmt::format("{}: not a sigrok session: no metadata file", name_));
        std::string text(std::size_t(std::min<zip_uint64_t>(st.size, 1 << 20)), '\0');
        zip_int64_t n = zip_fread(f, text.data(), text.size());
        zip_fclose(f);
        if (n < 0) throw InputError(fmt::format("{}: cannot read the metadata", name_));
        text.resize(std::size_t(n));

        const SrMetadata meta(text);
        const std::string* rate_text = meta.find("samplerate");
        if (!rate_text) throw InputError(fmt::format("{}: metadata has no samplerate", name_));
        const SampleRate rate = parseSampleRate(*rate_text, true);
        if (!rate.timebase)
            throw InputError(
                fmt::format("{}: samplerate '{}' {}", name_, printable(*rate_text), rate.problem));
        tb_ = *rate.timebase;
        const std::string* unit = meta.find("unitsize");
        if (!unit) throw InputError(fmt::format("{}: metadata has no unitsize", name_));
        unit_ = std::size_t(std::atoi(unit->c_str()));
        if (unit_ < 1 || unit_ > 8)
            throw InputError(fmt::format("{}: unitsize={} not supported (1 to 8 bytes per sample)",
                                         name_, printable(*unit)));
        const int total = std::max(meta.number("total probes"), meta.highestProbe());
        if (total > int(unit_ * 8))
            throw InputError(
                fmt::format("{}: {} probes do not fit in unitsize={}", name_, total, unit_));
        for (int bit = 0; bit < total; ++bit) {
            const std::string n = meta.probeName(bit);
            signals_.push_back({n, n, 1});
        }
        if (const std::string* file = meta.find("capturefile")) capturefile_ = *file;
    }

    void findChunks() {
        const std::string prefix = capturefile_.empty() ? "logic-1" : capturefile_;
        std::map<long, std::string> found;
        const zip_int64_t n = zip_get_num_entries(zip_, 0);
        for (zip_int64_t i = 0; i < n; ++i) {
            const char* nm = zip_get_name(zip_, zip_uint64_t(i), 0);
            if (!nm) continue;
            std::string s = nm;
            if (s.rfind(prefix + "-", 0) == 0) {
                const std::string num = s.substr(prefix.size() + 1);
                if (!num.empty() && num.find_first_not_of("0123456789") == std::string::npos)
                    found[std::atol(num.c_str())] = s;
            }
        }
        if (found.empty()) {
            zip_stat_t st;
            if (zip_stat(zip_, prefix.c_str(), 0, &st) == 0) {
                chunks_.push_back(prefix);  // old single-file session
                total_bytes_ = st.size;
                return;
            }
            throw InputError(fmt::format("{}: no logic data (no {}-1 chunk)", name_, prefix));
        }
        long expect = 1;
        for (const auto& [k, s] : found) {
            if (k != expect)
                throw InputError(fmt::format("{}: missing chunk {}-{}", name_, prefix, expect));
            chunks_.push_back(s);
            zip_stat_t st;
            if (zip_stat(zip_, s.c_str(), 0, &st) == 0) total_bytes_ += st.size;
            ++expect;
        }
        if (total_bytes_ % unit_ != 0)
            throw InputError(fmt::format(
                "{}: logic data of {} bytes is not a whole number of samples of unitsize={}", name_,
                total_bytes_, unit_));
    }

    // Moves the unread tail to the front and reads more, crossing chunk boundaries
    // (a sample may straddle two chunks). False when no whole word is left.
    bool refill() {
        const std::size_t tail = len_ - pos_;
        consumed_ += pos_;
        if (buf_.empty()) buf_.resize(1 << 18);
        std::memmove(buf_.data(), buf_.data() + pos_, tail);
        pos_ = 0;
        len_ = tail;
        while (len_ < unit_ || len_ < buf_.size() / 2) {
            if (!file_) {
                if (next_chunk_ >= chunks_.size()) break;
                file_ = openEntry(chunks_[next_chunk_]);
                if (!file_)
                    throw InputError(
                        fmt::format("{}: cannot read chunk {}", name_, chunks_[next_chunk_]));
                ++next_chunk_;
            }
            zip_int64_t n = zip_fread(file_, buf_.data() + len_, buf_.size() - len_);
            if (n < 0)
                throw InputError(
                    fmt::format("{}: corrupt chunk {}", name_, chunks_[next_chunk_ - 1]));
            if (n == 0) {
                zip_fclose(file_);
                file_ = nullptr;
                continue;
            }
            len_ += std::size_t(n);
        }
        return len_ >= unit_;
    }

    // The sample word at p: unitsize bytes, little-endian.
    std::uint64_t wordAt(const std::uint8_t* p) const {
        std::uint64_t w = 0;
        for (std::size_t b = 0; b < unit_; ++b)
            w |= std::uint64_t(p[b]) << (8 * b);
        return w;
    }

    bool readWord(std::uint64_t& w) {
        if (pos_ + unit_ > len_ && !refill()) return false;
        w = wordAt(buf_.data() + pos_);
        pos_ += unit_;
        return true;
    }

    std::string name_;
    OpenOptions opts_;
    std::unique_ptr<ZipArchive> archive_;
    zip_t* zip_ = nullptr;
    zip_file_t* file_ = nullptr;
    std::vector<std::string> chunks_;
    std::size_t next_chunk_ = 0;
    std::string capturefile_;
    Timebase tb_;  // one tick per sample
    std::size_t unit_ = 0;
    std::vector<SignalInfo> signals_;
    std::vector<Sel> sel_;
    std::uint64_t mask_ = 0;  // the selected probes' bits
    std::uint64_t prev_ = 0;  // the last sample, masked
    std::vector<std::uint8_t> buf_;
    std::size_t pos_ = 0, len_ = 0;
    std::uint64_t consumed_ = 0, total_bytes_ = 0;
    std::uint64_t sample_ = 0;  // index of the next word
    bool started_ = false, done_ = false;
};

}  // namespace

std::unique_ptr<CaptureReader> openSr(std::unique_ptr<ZipArchive> archive,
                                      const OpenOptions& opts) {
    return std::make_unique<SrReader>(std::move(archive), opts);
}

}  // namespace busdecode
