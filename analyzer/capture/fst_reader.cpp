// FST reader (GTKWave's and Verilator's compact trace format) through fstapi:
// - the file's block chain is checked first (fst_api.h), then fstapi reads the hierarchy:
//   scopes make full_name `a.b.sig`, a vector's range is not part of its name and a 1-bit
//   variable keeps its index (`bus[3]`), as the VCD reader names them; strings are not lines;
// - fstapi hands out value changes through a callback for a whole file at once, so a thread
//   of the reader's own runs it, masked to the selected signals, and hands the edges on in
//   blocks, a few at most in flight: memory stays flat;
// - levels as the VCD reader has them: x z u w - keep the line's level (1 before any level),
//   bit k of a vector counts from the LSB, a real reads 1 when nonzero; the initial levels
//   are those at the first time, edges come after it. --rate overrides the timescale.
#include <atomic>
#include <condition_variable>
#include <cstring>
#include <deque>
#include <exception>
#include <mutex>
#include <thread>

#include <fmt/format.h>
#include <unistd.h>

#include "core/options.h"
#include "core/sample_rate.h"
#include "fst_api.h"
#include "fstapi.h"
#include "readers.h"

namespace busdecode {

namespace {

constexpr std::size_t kBlocksInFlight = 4;

std::uint8_t levelOf(unsigned char c) {
    switch (c) {
        case '0':
        case 'l':
        case 'L':
            return 0;
        case '1':
        case 'h':
        case 'H':
            return 1;
        default:
            return 2;  // x z u w - and anything else: not a level
    }
}

bool isReal(unsigned char typ) {
    return typ == FST_VT_VCD_REAL || typ == FST_VT_VCD_REAL_PARAMETER ||
           typ == FST_VT_VCD_REALTIME || typ == FST_VT_SV_SHORTREAL;
}

// `data [7:0]` -> `data`; a 1-bit `bus [3]` -> `bus[3]` (what the VCD reader makes of them).
std::string referenceOf(const char* name, int width) {
    std::string ref = name, rest;
    if (const auto sp = ref.find(' '); sp != std::string::npos) {
        rest = ref.substr(ref.find_first_not_of(' ', sp) == std::string::npos
                              ? ref.size()
                              : ref.find_first_not_of(' ', sp));
        ref.erase(sp);
    }
    const auto lb = ref.find('[');
    if (width > 1 && lb != std::string::npos && lb > 0 && ref.back() == ']') ref.erase(lb);
    if (width == 1 && !rest.empty() && rest.front() == '[') ref += rest.substr(0, rest.find(' '));
    return ref;
}

Timebase timebaseOf(int exponent, const std::string& name) {
    if (exponent < -18 || exponent > 18)
        throw InputError(fmt::format("{}: FST timescale 1e{} s is out of range", name, exponent));
    std::int64_t p = 1;
    for (int i = 0; i < (exponent < 0 ? -exponent : exponent); ++i)
        p *= 10;
    return exponent < 0 ? Timebase{1, p} : Timebase{p, 1};
}

class FstReader : public CaptureReader {
public:
    FstReader(const std::string& path, std::string name, const OpenOptions& opts, int owned_fd)
        : name_(std::move(name)), owned_fd_(owned_fd) {
        checkFstBlocks(path, name_);
        ctx_.reset(fstReaderOpen(path.c_str()));
        if (!ctx_) throw InputError(fmt::format("{}: fstapi cannot read this FST file", name_));
        tb_ = timebaseOf(fstReaderGetTimescale(ctx_.get()), name_);
        if (opts.rate_hz > 0) {  // one sample per time unit (as for VCD)
            const SampleRate r = sampleRateOf(opts.rate_hz);
            if (!r.timebase)
                throw InputError(fmt::format("--rate {}: {}", opts.rate_hz, r.problem));
            tb_ = *r.timebase;
        }
        start_ = checkedTick(fstReaderGetStartTime(ctx_.get()));
        end_ = std::max(start_, checkedTick(fstReaderGetEndTime(ctx_.get())));
        readHierarchy();
    }
    ~FstReader() override {
        {
            std::lock_guard<std::mutex> lock(m_);
            cancel_ = true;
        }
        cv_.notify_all();
        if (worker_.joinable()) worker_.join();
        ctx_.reset();
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
    struct Var {
        fstHandle handle;
        bool real;
    };
    struct Target {
        std::uint32_t line;
        int bit;
        bool real;
    };

    Tick checkedTick(std::uint64_t t) const {
        if (t > std::uint64_t(kMaxEdgeTick))
            throw InputError(fmt::format("{}: time beyond 2^55 - 1 ticks ({})", name_, t));
        return Tick(t);
    }
    void readHierarchy();
    void produce();
    void change(std::uint64_t time, fstHandle handle, const unsigned char* value);
    void publishInitial();
    void handOff();
    static void onChange(void* self, std::uint64_t time, fstHandle handle,
                         const unsigned char* value) {
        static_cast<FstReader*>(self)->change(time, handle, value);
    }

    std::string name_;
    int owned_fd_;
    FstContext ctx_;
    Timebase tb_;
    Tick start_ = 0, end_ = 0;
    std::vector<SignalInfo> signals_;
    std::vector<Var> vars_;  // per signal

    // Selected lines by handle: targets_[first_[h] .. first_[h + 1]).
    std::vector<std::uint32_t> first_;
    std::vector<Target> targets_;
    std::size_t line_count_ = 0;

    // The producer thread's own state.
    std::vector<std::uint8_t> level_;
    std::vector<Edge> filling_;
    Tick last_ = 0;
    bool published_ = false;
    std::uint64_t unknown_states_ = 0;  // read by notes() after the end

    // Shared with the consumer, under m_.
    std::mutex m_;
    std::condition_variable cv_;
    std::deque<std::vector<Edge>> full_;
    std::vector<std::vector<Edge>> spare_;
    std::vector<std::uint8_t> initial_;
    bool initial_ready_ = false, done_ = false;
    std::atomic<bool> cancel_{false};  // also read by the callback, without the lock
    std::exception_ptr error_;
    std::thread worker_;
};

void FstReader::readHierarchy() {
    std::vector<std::string> scopes;
    while (const fstHier* h = fstReaderIterateHier(ctx_.get())) {
        if (h->htyp == FST_HT_SCOPE) {
            scopes.emplace_back(h->u.scope.name ? h->u.scope.name : "");
        } else if (h->htyp == FST_HT_UPSCOPE) {
            if (!scopes.empty()) scopes.pop_back();
        } else if (h->htyp == FST_HT_VAR && h->u.var.typ != FST_VT_GEN_STRING &&
                   h->u.var.handle > 0 && h->u.var.name) {
            const bool real = isReal(h->u.var.typ);
            // A real's length is its 8 bytes; VCD declares it `real 64`.
            const int width = real ? 64 : int(std::max<std::uint32_t>(1, h->u.var.length));
            std::string ref = referenceOf(h->u.var.name, width), full;
            for (const auto& s : scopes)
                if (!s.empty()) full += s + ".";
            signals_.push_back({ref, full + ref, width});
            vars_.push_back({h->u.var.handle, real});
        }
    }
}

void FstReader::select(const std::vector<LineRef>& lines) {
    checkSelection(lines);
    const fstHandle max = fstReaderGetMaxHandle(ctx_.get());
    std::vector<std::vector<Target>> by_handle(max + 1);
    for (std::size_t i = 0; i < lines.size(); ++i) {
        const LineRef& l = lines[i];
        if (l.signal < 0 || l.signal >= int(vars_.size()))
            throw std::out_of_range("FstReader::select");
        const Var& v = vars_[std::size_t(l.signal)];
        if (v.handle > max) throw InputError(fmt::format("{}: handle beyond the geometry", name_));
        by_handle[v.handle].push_back({std::uint32_t(i), l.bit < 0 ? 0 : l.bit, v.real});
    }
    first_.assign(std::size_t(max) + 2, 0);
    targets_.clear();
    fstReaderClrFacProcessMaskAll(ctx_.get());
    for (fstHandle h = 0; h <= max; ++h) {
        first_[h] = std::uint32_t(targets_.size());
        targets_.insert(targets_.end(), by_handle[h].begin(), by_handle[h].end());
        if (!by_handle[h].empty()) fstReaderSetFacProcessMask(ctx_.get(), h);
    }
    first_[std::size_t(max) + 1] = std::uint32_t(targets_.size());
    line_count_ = lines.size();
}

std::vector<std::uint8_t> FstReader::initialLevels() {
    level_.assign(line_count_, 1);
    last_ = start_;
    filling_.reserve(kEdgeBlockSize);
    worker_ = std::thread([this] { produce(); });
    std::unique_lock<std::mutex> lock(m_);
    cv_.wait(lock, [&] { return initial_ready_ || done_; });
    if (!initial_ready_ && error_) std::rethrow_exception(std::exchange(error_, nullptr));
    return initial_;
}

void FstReader::produce() {
    try {
        fstReaderIterBlocksSetNativeDoublesOnCallback(ctx_.get(), 1);
        fstReaderIterBlocks2(ctx_.get(), &FstReader::onChange, nullptr, this, nullptr);
        if (!published_) publishInitial();
        handOff();
    } catch (const FstApiFatal& e) {
        std::lock_guard<std::mutex> lock(m_);
        error_ = std::make_exception_ptr(InputError(fmt::format("{}: {}", name_, e.what())));
    } catch (...) {
        std::lock_guard<std::mutex> lock(m_);
        error_ = std::current_exception();
    }
    {
        std::lock_guard<std::mutex> lock(m_);
        done_ = true;
    }
    cv_.notify_all();
}

void FstReader::change(std::uint64_t time, fstHandle handle, const unsigned char* value) {
    if (cancel_) {  // the reader is going away: fstapi skips the blocks after this one
        fstReaderSetLimitTimeRange(ctx_.get(), 0, 0);
        return;
    }
    const Tick t = checkedTick(time);
    if (t < last_)
        throw InputError(
            fmt::format("{}: a value change at {} after one at {} (times going "
                        "backwards)",
                        name_, t, last_));
    if (t > start_ && !published_) publishInitial();
    last_ = t;
    end_ = std::max(end_, t);
    if (first_.empty() || handle >= first_.size() - 1) return;
    std::size_t len = 0;  // of a bit string (a real's value is 8 bytes, not a string)
    if (first_[handle] != first_[handle + 1] && !targets_[first_[handle]].real)
        len = std::strlen(reinterpret_cast<const char*>(value));
    for (std::uint32_t k = first_[handle]; k < first_[handle + 1]; ++k) {
        const Target& g = targets_[k];
        std::uint8_t level;
        if (g.real) {
            double d;
            std::memcpy(&d, value, sizeof d);
            level = d != 0;
        } else {
            level = std::size_t(g.bit) < len ? levelOf(value[len - 1 - std::size_t(g.bit)]) : 2;
        }
        if (level > 1) {
            ++unknown_states_;
            continue;
        }
        if (level == level_[g.line]) continue;
        level_[g.line] = level;
        if (!published_) continue;
        filling_.push_back(Edge(t, g.line, level));
        if (filling_.size() == kEdgeBlockSize) handOff();
    }
}

void FstReader::publishInitial() {
    published_ = true;
    {
        std::lock_guard<std::mutex> lock(m_);
        initial_ = level_;
        initial_ready_ = true;
    }
    cv_.notify_all();
}

// Queues the filled block (waiting while kBlocksInFlight are queued) and takes a spare.
void FstReader::handOff() {
    std::unique_lock<std::mutex> lock(m_);
    cv_.wait(lock, [&] { return full_.size() < kBlocksInFlight || cancel_; });
    if (cancel_) {
        filling_.clear();
        return;
    }
    if (!filling_.empty()) full_.push_back(std::move(filling_));
    if (!spare_.empty()) {
        filling_ = std::move(spare_.back());
        spare_.pop_back();
    } else {
        filling_ = {};
        filling_.reserve(kEdgeBlockSize);
    }
    filling_.clear();
    lock.unlock();
    cv_.notify_all();
}

bool FstReader::next(EdgeBlock& block) {
    std::unique_lock<std::mutex> lock(m_);
    cv_.wait(lock, [&] { return !full_.empty() || done_; });
    if (full_.empty()) {
        if (error_) std::rethrow_exception(std::exchange(error_, nullptr));
        block.clear();
        block.known_until = end_;
        return false;
    }
    spare_.push_back(std::move(block.edges));
    block.clear();  // (no voltages: FST holds levels)
    block.edges = std::move(full_.front());
    full_.pop_front();
    block.known_until = block.edges.back().t;
    lock.unlock();
    cv_.notify_all();
    return true;
}

}  // namespace

std::unique_ptr<CaptureReader> openFst(const std::string& path, const std::string& name,
                                       const OpenOptions& opts, int owned_fd) {
    // Until FstReader is made, the descriptor is still ours to close.
    try {
        return std::make_unique<FstReader>(path, name, opts, owned_fd);
    } catch (const FstApiFatal& e) {
        if (owned_fd >= 0) ::close(owned_fd);
        throw InputError(fmt::format("{}: {}", name, e.what()));
    } catch (...) {
        if (owned_fd >= 0) ::close(owned_fd);
        throw;
    }
}

}  // namespace busdecode
