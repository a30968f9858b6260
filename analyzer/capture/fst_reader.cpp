// FST reader (GTKWave's and Verilator's compact trace format) through fstapi:
// - the file's block chain is checked first (fst_api.h), then fstapi reads the file in a
//   child process (fst_api_process.h, fst_reader_child.cpp): a corrupt compressed block
//   that makes fstapi crash, or take more than its memory budget, ends that child only
//   and becomes one InputError naming the file and the block;
// - the child sends the signals, then, once told the selection, the initial levels and
//   blocks of edges; --rate overrides the timescale (one sample per time unit, as for VCD).
#include <cstring>
#include <filesystem>

#include <fmt/format.h>
#include <unistd.h>

#include "core/options.h"
#include "core/sample_rate.h"
#include "fst_api.h"
#include "fst_api_process.h"
#include "fst_reader_child.h"
#include "readers.h"

namespace busdecode {

namespace {

Timebase timebaseOf(int exponent, const std::string& name) {
    if (exponent < -18 || exponent > 18)
        throw InputError(fmt::format("{}: FST timescale 1e{} s is out of range", name, exponent));
    std::int64_t p = 1;
    for (int i = 0; i < (exponent < 0 ? -exponent : exponent); ++i)
        p *= 10;
    return exponent < 0 ? Timebase{1, p} : Timebase{p, 1};
}

// The child's processor time: far more than fstapi takes to unpack the file (well over
// 10 MB a second), so only a loop in it runs out.
std::uint64_t fstCpuSeconds(const std::string& path) {
    std::error_code ec;
    const std::uintmax_t size = std::filesystem::file_size(path, ec);
    return 30 + (ec ? 0 : std::uint64_t(size >> 20));
}

class FstReader : public CaptureReader {
public:
    FstReader(const std::string& path, std::string name, const OpenOptions& opts, int owned_fd)
        : name_(std::move(name)),
          owned_fd_(owned_fd),
          chain_(checkFstBlocks(path, name_)),
          child_(name_, kFstBlockBudget, fstCpuSeconds(path),
                 [&](ChildChannel& channel) { serveFst(path, name_, channel); }) {
        readHeader(expect(fst_message::Header, "its header and hierarchy"));
        if (opts.rate_hz > 0) {  // one sample per time unit (as for VCD)
            const SampleRate r = sampleRateOf(opts.rate_hz);
            if (!r.timebase)
                throw InputError(fmt::format("--rate {}: {}", opts.rate_hz, r.problem));
            tb_ = *r.timebase;
        }
    }
    ~FstReader() override {
        if (owned_fd_ >= 0) ::close(owned_fd_);
    }

    const std::vector<SignalInfo>& signals() const override { return signals_; }
    Timebase timebase() const override { return tb_; }
    std::string formatName() const override { return "fst"; }
    bool changesOnly() const override { return true; }
    bool readsAhead() const override { return true; }
    Tick startTick() const override { return start_; }
    Tick endTick() const override { return end_; }
    std::vector<std::string> notes() const override {
        if (unknown_states_ == 0) return {};
        return {
            fmt::format("{} value changes of mapped lines to x, z, u, w or -: each kept the "
                        "line's level before it",
                        unknown_states_)};
    }

    void select(const std::vector<LineRef>& lines) override;
    std::vector<std::uint8_t> initialLevels() override;
    bool next(EdgeBlock& block) override;

private:
    std::string expect(std::uint8_t kind, const char* what);
    void readHeader(const std::string& payload);
    Tick checkedTick(std::uint64_t t) const {
        if (t > std::uint64_t(kMaxEdgeTick))
            throw InputError(fmt::format("{}: time beyond 2^55 - 1 ticks ({})", name_, t));
        if (t > std::uint64_t(lastTickOf(tb_)))
            throw InputError(fmt::format(
                "{}: time {} beyond what times in ns can hold at this timescale", name_, t));
        return Tick(t);
    }

    std::string name_;
    int owned_fd_;
    FstBlockChain chain_;
    FstChild child_;
    Timebase tb_;
    Tick start_ = 0, end_ = 0, last_ = 0;
    std::vector<SignalInfo> signals_;
    std::size_t line_count_ = 0;
    bool ended_ = false;
    std::uint64_t unknown_states_ = 0;
};

// The child's next message, which must be `kind` (or the End after the edges); its error
// or its death as an InputError, naming the block it was in when it died.
std::string FstReader::expect(std::uint8_t kind, const char* what) {
    std::uint8_t got = 0;
    std::string payload;
    if (!child_.channel().receive(got, payload)) {
        const std::string how = child_.howItEnded();
        if (kind == fst_message::Header)
            throw InputError(fmt::format("{}: fstapi failed reading {} ({}: a corrupt block)",
                                         name_, what, how));
        throw InputError(
            fmt::format("{}: FST {}: fstapi failed unpacking it ({}: a corrupt "
                        "block, or one needing more than {} MB)",
                        name_, chain_.blockAt(std::uint64_t(last_)), how, kFstBlockBudget >> 20));
    }
    if (got == fst_message::Error) throw InputError(payload);
    if (got != kind && !(kind == fst_message::Edges && got == fst_message::End))
        throw InputError(fmt::format("{}: the FST reader's child sent message {} for {}", name_,
                                     int(got), what));
    if (got == fst_message::End) {
        PayloadReader in(payload);
        end_ = std::max(end_, checkedTick(in.u64()));
        unknown_states_ = in.u64();
        ended_ = true;
        return {};
    }
    return payload;
}

void FstReader::readHeader(const std::string& payload) {
    PayloadReader in(payload);
    tb_ = timebaseOf(int(std::int64_t(in.u64())), name_);
    start_ = checkedTick(in.u64());
    end_ = std::max(start_, checkedTick(in.u64()));
    last_ = start_;
    const std::uint64_t count = in.u64();
    for (std::uint64_t i = 0; i < count; ++i) {
        std::string ref = in.text(), full = in.text();
        const int width = int(in.u64());
        signals_.push_back({std::move(ref), std::move(full), width});
        signals_.back().msb = int(in.u64()) - 1;  // -1: no declared range
        signals_.back().lsb = int(in.u64()) - 1;
    }
}

void FstReader::select(const std::vector<LineRef>& lines) {
    checkSelection(lines);
    PayloadWriter out;
    out.u64(lines.size());
    for (const LineRef& l : lines) {
        if (l.signal < 0 || l.signal >= int(signals_.size()))
            throw std::out_of_range("FstReader::select");
        out.u64(std::uint64_t(l.signal)).u64(std::uint64_t(std::int64_t(l.bit)));
    }
    line_count_ = lines.size();
    try {
        child_.channel().send(fst_message::Select, out.bytes());
    } catch (const ChannelClosed&) {  // died after the header: its reason comes next
    }
}

std::vector<std::uint8_t> FstReader::initialLevels() {
    const std::string levels = expect(fst_message::Initial, "the initial levels");
    if (levels.size() != line_count_)
        throw InputError(fmt::format("{}: the FST reader's child sent {} levels for {} lines",
                                     name_, levels.size(), line_count_));
    return {levels.begin(), levels.end()};
}

bool FstReader::next(EdgeBlock& block) {
    block.clear();  // (no voltages: FST holds levels)
    if (!ended_) {
        const std::string edges = expect(fst_message::Edges, "the value changes");
        if (!ended_) {
            block.edges.resize(edges.size() / sizeof(Edge));
            std::memcpy(static_cast<void*>(block.edges.data()), edges.data(),
                        block.edges.size() * sizeof(Edge));
            if (!block.edges.empty()) last_ = block.edges.back().t;
            block.known_until = last_;
            return true;
        }
    }
    block.known_until = end_;
    return false;
}

}  // namespace

std::unique_ptr<CaptureReader> openFst(const std::string& path, const std::string& name,
                                       const OpenOptions& opts, int owned_fd) {
    // Until FstReader is made, the descriptor is still ours to close.
    try {
        return std::make_unique<FstReader>(path, name, opts, owned_fd);
    } catch (...) {
        if (owned_fd >= 0) ::close(owned_fd);
        throw;
    }
}

}  // namespace busdecode
