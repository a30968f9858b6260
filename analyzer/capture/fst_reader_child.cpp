// The FST reader's child side: fstapi reads the hierarchy, then the value changes of the
// selected signals through its callback, made into edges as the VCD reader has them:
// - scopes make full_name `a.b.sig`, a vector's range is not part of its name and a 1-bit
//   variable keeps its index (`bus[3]`); strings are not lines;
// - x z u w - keep the line's level (1 before any level), bit k of a vector counts from
//   the LSB, a real reads 1 when nonzero; the initial levels are those at the first time,
//   edges come after it. The edges go to the parent a block at a time: the socket's
//   buffer is all that runs ahead, so memory stays flat.
#include "fst_reader_child.h"

#include <algorithm>
#include <cstring>
#include <new>
#include <vector>

#include <fmt/format.h>

#include "core/edge.h"
#include "core/options.h"
#include "fst_api.h"
#include "fstapi.h"
#include "vector_range.h"

namespace busdecode {

namespace {

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

// `data [7:0]`, as FST names a vector: its reference and range as the VCD reader reads them.
VectorName referenceOf(const char* name, int width) {
    const std::string_view n = name;
    const auto sp = n.find(' ');
    if (sp == std::string_view::npos) return splitVectorName(n, "", width);
    std::string_view after = n.substr(std::min(n.find_first_not_of(' ', sp), n.size()));
    return splitVectorName(n.substr(0, sp), after.substr(0, after.find(' ')), width);
}

class FstProducer {
public:
    FstProducer(const std::string& path, std::string name, ChildChannel& channel)
        : name_(std::move(name)), channel_(channel) {
        ctx_.reset(fstReaderOpen(path.c_str()));
        if (!ctx_) throw InputError(fmt::format("{}: fstapi cannot read this FST file", name_));
    }
    void sendHeader();
    bool receiveSelection();
    void run();

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
    void change(std::uint64_t time, fstHandle handle, const unsigned char* value);
    void publishInitial();
    void sendEdges();
    static void onChange(void* self, std::uint64_t time, fstHandle handle,
                         const unsigned char* value) {
        static_cast<FstProducer*>(self)->change(time, handle, value);
    }

    std::string name_;
    ChildChannel& channel_;
    FstContext ctx_;
    std::vector<Var> vars_;  // per signal
    Tick start_ = 0, end_ = 0, last_ = 0;
    // Selected lines by handle: targets_[first_[h] .. first_[h + 1]).
    std::vector<std::uint32_t> first_;
    std::vector<Target> targets_;
    std::vector<std::uint8_t> level_;
    std::vector<Edge> filling_;
    bool published_ = false;
    std::uint64_t unknown_states_ = 0;
};

void FstProducer::sendHeader() {
    void* ctx = ctx_.get();
    start_ = checkedTick(fstReaderGetStartTime(ctx));
    end_ = std::max(start_, checkedTick(fstReaderGetEndTime(ctx)));
    PayloadWriter signals;
    std::vector<std::string> scopes;
    std::uint64_t count = 0;
    while (const fstHier* h = fstReaderIterateHier(ctx)) {
        if (h->htyp == FST_HT_SCOPE) {
            scopes.emplace_back(h->u.scope.name ? h->u.scope.name : "");
        } else if (h->htyp == FST_HT_UPSCOPE) {
            if (!scopes.empty()) scopes.pop_back();
        } else if (h->htyp == FST_HT_VAR && h->u.var.typ != FST_VT_GEN_STRING &&
                   h->u.var.handle > 0 && h->u.var.name) {
            const bool real = isReal(h->u.var.typ);
            // A real's length is its 8 bytes; VCD declares it `real 64`.
            const int width = real ? 64 : int(std::max<std::uint32_t>(1, h->u.var.length));
            const VectorName v = referenceOf(h->u.var.name, width);
            std::string full;
            for (const auto& s : scopes)
                if (!s.empty()) full += s + ".";
            signals.text(v.ref).text(full + v.ref).u64(std::uint64_t(width));
            signals.u64(std::uint64_t(v.msb + 1)).u64(std::uint64_t(v.lsb + 1));  // 0: none
            vars_.push_back({h->u.var.handle, real});
            ++count;
        }
    }
    PayloadWriter head;
    head.u64(std::uint64_t(std::int64_t(fstReaderGetTimescale(ctx))))
        .u64(std::uint64_t(start_))
        .u64(std::uint64_t(end_))
        .u64(count);
    channel_.send(fst_message::Header, head.bytes() + signals.bytes());
}

// The parent's selection (indices it checked against the header's signals).
bool FstProducer::receiveSelection() {
    std::uint8_t kind;
    std::string payload;
    if (!channel_.receive(kind, payload) || kind != fst_message::Select) return false;
    PayloadReader in(payload);
    const std::size_t lines = std::size_t(in.u64());
    const fstHandle max = fstReaderGetMaxHandle(ctx_.get());
    std::vector<std::vector<Target>> by_handle(std::size_t(max) + 1);
    for (std::size_t i = 0; i < lines; ++i) {
        const Var& v = vars_.at(std::size_t(in.u64()));
        const int bit = int(std::int64_t(in.u64()));
        if (v.handle > max) throw InputError(fmt::format("{}: handle beyond the geometry", name_));
        by_handle[v.handle].push_back({std::uint32_t(i), bit < 0 ? 0 : bit, v.real});
    }
    first_.assign(std::size_t(max) + 2, 0);
    fstReaderClrFacProcessMaskAll(ctx_.get());
    for (fstHandle h = 0; h <= max; ++h) {
        first_[h] = std::uint32_t(targets_.size());
        targets_.insert(targets_.end(), by_handle[h].begin(), by_handle[h].end());
        if (!by_handle[h].empty()) fstReaderSetFacProcessMask(ctx_.get(), h);
    }
    first_[std::size_t(max) + 1] = std::uint32_t(targets_.size());
    level_.assign(lines, 1);
    return true;
}

void FstProducer::run() {
    last_ = start_;
    filling_.reserve(kEdgeBlockSize);
    fstReaderIterBlocksSetNativeDoublesOnCallback(ctx_.get(), 1);
    fstReaderIterBlocks2(ctx_.get(), &FstProducer::onChange, nullptr, this, nullptr);
    if (!published_) publishInitial();
    sendEdges();
    channel_.send(fst_message::End,
                  PayloadWriter().u64(std::uint64_t(end_)).u64(unknown_states_).bytes());
}

void FstProducer::change(std::uint64_t time, fstHandle handle, const unsigned char* value) {
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
        if (filling_.size() == kEdgeBlockSize) sendEdges();
    }
}

void FstProducer::publishInitial() {
    published_ = true;
    channel_.send(fst_message::Initial,
                  std::string_view(reinterpret_cast<const char*>(level_.data()), level_.size()));
}

void FstProducer::sendEdges() {
    if (filling_.empty()) return;
    channel_.send(fst_message::Edges,
                  std::string_view(reinterpret_cast<const char*>(filling_.data()),
                                   filling_.size() * sizeof(Edge)));
    filling_.clear();
}

}  // namespace

void serveFst(const std::string& path, const std::string& name, ChildChannel& channel) {
    std::string error;
    try {
        FstProducer producer(path, name, channel);
        producer.sendHeader();
        if (!producer.receiveSelection()) return;  // the parent only wanted the signals
        producer.run();
        return;
    } catch (const ChannelClosed&) {
        throw;
    } catch (const InputError& e) {
        error = e.what();
    } catch (const FstApiFatal& e) {
        error = fmt::format("{}: {}", name, e.what());
    } catch (const std::bad_alloc&) {
        error = fmt::format("{}: fstapi ran out of the {} MB it may take for a block", name,
                            kFstBlockBudget >> 20);
    }
    channel.send(fst_message::Error, error);
}

}  // namespace busdecode
