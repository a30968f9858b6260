// Decoder targets: fuzz bytes become a random edge stream on the decoder's roles, with
// random options within their declared ranges, decoded by a real Session over an
// in-memory capture. Findings: crashes and sanitizer reports, hangs, unbounded memory,
// exceptions out of run(), events out of order or ending before they start, and more
// events than the edges can explain.
//
// Input layout (every byte optional: missing bytes read as zero):
//   timebase choice, flags (optional roles left unbound, glitch filter, output reading
//   no fields as text does), initial levels,
//   start offset (varint, negated), one or two bytes per option, then edges:
//   a byte [bits 0-2 role, bit 3 explicit level, bit 4 that level, bits 5-7 delta kind]
//   followed by the delta's bytes.
// The decoder is also fed the same edges directly three ways, through its general path,
// through edge() and in blocks through edges(): all must give the same events
// (checkBlocksMatchEdges). With the flags' top bit, a decoder that can be spliced
// (a SpliceableDecoder) also decodes the edges written as a VCD file the same in order and
// in about eight pieces (61 bytes or more), each piece decoded ahead and spliced in
// (checkPiecesMatchInOrder, core/piece_speculation.h).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>

#include "byte_stream.h"
#include "capture/capture_reader.h"
#include "capture/capture_writer.h"
#include "core/registry.h"
#include "core/scratch_dir.h"
#include "core/session.h"
#include "core/splicing.h"
#include "core/waveform.h"
#include "declared_fields.h"
#include "fuzz_harness.h"
#include "reader_targets.h"
#include "sinks/event_format.h"
#include "support/feed/direct_feed.h"

namespace busdecode::fuzz {

namespace {

[[noreturn]] void failure(const std::string& what) {
    throw HarnessFailure(what);
}

const Timebase kTimebases[] = {
    {1, 1'000'000'000},          // 1 ns (generators, VCD)
    {1, 100'000'000},            // 100 MHz sampling
    {1, 24'000'000},             // 24 MHz (sigrok's fx2lafw)
    {1, 1'000'000'000'000},      // 1 ps VCD
    {1, 1'000'000},              // 1 MHz (caliper)
    {10, 1'000'000'000},         // 10 ns VCD
    {1, 5},                      // a wrongly stated rate (5 Hz)
    {1, 1'000'000'000'000'000},  // 1 fs
};

std::string numberText(double v) {
    return fmt::format("{}", v);
}

// One option value from the bytes, always inside the spec's range / choices.
std::string optionValue(const OptionSpec& o, ByteStream& in) {
    using K = OptionSpec::Kind;
    switch (o.kind) {
        case K::Bool:
            return (in.byte() & 1) ? "1" : "0";
        case K::Choice:
            if (o.choices.empty()) return o.default_value;
            return o.choices[in.byte() % o.choices.size()];
        case K::String:
            return o.default_value;
        case K::Int:
        case K::Float: {
            const std::uint8_t mode = in.byte(), arg = in.byte();
            const bool integer = o.kind == K::Int;
            const double lo = std::max(o.min, integer ? -1e18 : -1e300);
            const double hi = std::min(o.max, integer ? 1e18 : 1e300);
            double v;
            switch (mode % 7) {
                case 0:
                    return o.default_value;
                case 1:
                    v = lo;
                    break;
                case 2:
                    v = hi;
                    break;
                case 3:
                    v = std::min(hi, lo + arg);
                    break;
                case 4: {  // log-uniform over the positive part of the range
                    const double a = std::max(lo, 1e-3), b = std::max(hi, a);
                    v = a * std::pow(b / a, arg / 255.0);
                    break;
                }
                case 5:
                    if (o.allow_auto) return "auto";
                    v = std::min(hi, std::max(lo, double(arg)));
                    break;
                default:  // an exact value (seeds use it): varint, or the bits of a double
                    if (integer) {
                        v = double(std::int64_t(in.varint()));
                    } else {
                        std::uint64_t bits = in.varint();
                        std::memcpy(&v, &bits, sizeof v);
                        if (!std::isfinite(v)) v = lo;
                    }
                    break;
            }
            v = std::min(hi, std::max(lo, v));
            if (integer) {
                v = v < 0 ? std::ceil(v) : std::floor(v);
                return std::to_string(std::int64_t(v));
            }
            return numberText(v);
        }
    }
    return o.default_value;
}

std::uint64_t deltaOf(int kind, ByteStream& in) {
    switch (kind) {
        case 0:
            return 0;
        case 1:
            return in.byte();
        case 2:
            return std::uint64_t(in.byte()) << 4;
        case 3:
            return std::uint64_t(in.byte()) << 8;
        case 4:
            return in.varint();
        case 5:
            return std::uint64_t(in.byte()) << 16;
        case 6:
            return in.varint() << 16;
        default:
            return in.varint() << 32;
    }
}

struct CheckingSink : OutputSink {
    std::vector<DecoderRequest> requests;
    std::uint64_t events = 0;
    Tick last_start = std::numeric_limits<Tick>::min();
    bool reads_fields = true;  // false: as text output, which prints the summary
    bool readsFields() const override { return reads_fields; }
    void onEvent(const Event& e, const CaptureFacts&) override {
        ++events;
        if (!reads_fields && e.summary.empty() && e.fields.empty())
            failure(fmt::format("{} {} has neither a summary nor fields for text output", e.proto,
                                e.type));
        if (e.end < e.start)
            failure(fmt::format("{} {} ends ({}) before it starts ({})", e.proto, e.type, e.end,
                                e.start));
        if (e.start < last_start) failure(fmt::format("{} {} out of time order", e.proto, e.type));
        last_start = e.start;
        if (const std::string wrong = undeclaredField(e, requests); !wrong.empty()) failure(wrong);
    }
};

// The decoder fed directly the edges a session would hand it (mapped lines only, each
// a change of its line's level), three times: one at a time through its general path
// (FastDecoder::edgeReference), one at a time through edge(), and through edges() in blocks
// of five and of a session's size. Every event, field for field, and the advice must be
// the same. BiSS-C takes a frame's data in runs with the frame's state in locals
// (BisscDecoder::dataRun), SPI 64 edges at a time as bit masks (SpiDecoder::edges): this
// is the oracle for those loops.
void checkBlocksMatchEdges(const DecoderFactory& factory, const Waveform& w,
                           const DecoderRequest& req, const std::vector<int>& line_of_role) {
    std::vector<std::string> reference, one_by_one, in_blocks, in_big_blocks;
    try {
        const Options options = Options::resolve(factory.info(), req.options);
        reference = decodeDirectly(factory, options, w, line_of_role, Feed::Reference);
        one_by_one = decodeDirectly(factory, options, w, line_of_role, Feed::OneByOne);
        in_blocks = decodeDirectly(factory, options, w, line_of_role, Feed::Blocks, 5);
        in_big_blocks =
            decodeDirectly(factory, options, w, line_of_role, Feed::Blocks, kEdgeBlockSize);
    } catch (const InputError&) {
        return;  // refused up front, as decodeChecked() found
    }
    for (const auto* fed : {&one_by_one, &in_blocks, &in_big_blocks}) {
        for (std::size_t i = 0; i < std::max(reference.size(), fed->size()); ++i) {
            const std::string a = i < reference.size() ? reference[i] : "(none)";
            const std::string b = i < fed->size() ? (*fed)[i] : "(none)";
            if (a != b)
                failure(fmt::format("event {} on the general path: {}; {}: {}", i, a,
                                    fed == &one_by_one  ? "through edge()"
                                    : fed == &in_blocks ? "in blocks of 5"
                                                        : "in blocks of 16384",
                                    b));
        }
    }
}

// Every event as its JSON line; like jsonl output it reads no summaries, so the pieces
// are decoded as `decode --format jsonl` decodes them.
class JsonLines final : public OutputSink {
public:
    bool readsSummaries() const override { return false; }
    void onEvent(const Event& e, const CaptureFacts& facts) override {
        lines.push_back(eventToJson(e, facts.timebase));
    }
    std::vector<std::string> lines;
};

void checkPiecesMatchInOrder(const DecoderFactory& factory, const Waveform& w,
                             const DecoderRequest& req) {
    try {
        if (!splicingOf(*factory.create(Options::resolve(factory.info(), req.options)))) return;
    } catch (const InputError&) {
        return;  // refused up front, as decodeChecked() found
    }
    const ScratchDir dir("busdecode-fuzz");
    const std::string path = dir.path() + "/edges.vcd";
    std::uint64_t piece_bytes = 61;
    auto decode = [&](bool in_pieces, std::vector<std::string>& lines, Session::PieceStats& st) {
        OpenOptions o;
        o.read_ahead = in_pieces;
        o.vcd_piece_bytes = piece_bytes;
        o.vcd_boundary_search = 4096;
        auto reader = openCapture(path, o);
        Session session({req}, *reader, "fuzz");
        JsonLines sink;
        session.addSink(&sink);
        session.run();
        lines = std::move(sink.lines);
        st = session.pieceStats();
    };
    std::vector<std::string> in_order, in_pieces;
    Session::PieceStats stats;
    try {
        writeVcd(w, path);
        // About eight pieces, 61 bytes or more: each piece costs a mapping and a decoder
        // started ahead, and hundreds of them a file held the target to 600 inputs a second.
        piece_bytes = std::max<std::uint64_t>(61, std::filesystem::file_size(path) / 8 + 1);
        decode(false, in_order, stats);
    } catch (const std::exception&) {
        return;  // edges a VCD file cannot hold, or read back otherwise: not this check's
    }
    try {
        decode(true, in_pieces, stats);
    } catch (const std::exception& e) {
        failure(std::string("decoding in pieces threw: ") + e.what());
    }
    for (std::size_t i = 0; i < std::max(in_order.size(), in_pieces.size()); ++i) {
        const std::string a = i < in_order.size() ? in_order[i] : "(none)";
        const std::string b = i < in_pieces.size() ? in_pieces[i] : "(none)";
        if (a != b)
            failure(fmt::format("event {} in order: {}; in pieces ({} of {} spliced in): {}", i, a,
                                stats.spliced, stats.pieces, b));
    }
}

}  // namespace

void runDecoderTarget(const std::string& id, const std::uint8_t* data, std::size_t size) {
    registerDecoders();
    const DecoderFactory* factory = Registry::instance().find(id);
    if (!factory) failure("decoder '" + id + "' is not built in");
    const DecoderInfo& info = factory->info();
    ByteStream in(data, size);

    Waveform w;
    w.timebase = kTimebases[in.byte() % std::size(kTimebases)];
    const std::uint8_t flags = in.byte();
    const std::uint8_t initial = in.byte();
    const Tick start = -Tick(in.varint() % (std::uint64_t(1) << 40));

    // Roles: required ones always bound; optional role k unbound when flag bit k is set,
    // but at least one of need_one_of stays bound.
    DecoderRequest req;
    req.proto = id;
    std::vector<int> line_of_role(info.roles.size(), -1);
    for (std::size_t r = 0; r < info.roles.size(); ++r) {
        if (!info.roles[r].required && r < 4 && (flags >> r) & 1) continue;
        line_of_role[r] = int(w.names.size());
        w.names.push_back(info.roles[r].name);
        req.map[info.roles[r].name] = info.roles[r].name;
    }
    if (!info.need_one_of.empty()) {
        bool any = false;
        for (std::size_t r = 0; r < info.roles.size(); ++r)
            for (const auto& n : info.need_one_of)
                any |= info.roles[r].name == n && line_of_role[r] >= 0;
        if (!any) {
            for (std::size_t r = 0; r < info.roles.size(); ++r)
                if (info.roles[r].name == info.need_one_of.front()) {
                    line_of_role[r] = int(w.names.size());
                    w.names.push_back(info.roles[r].name);
                    req.map[info.roles[r].name] = info.roles[r].name;
                }
        }
    }
    const std::size_t nlines = w.names.size();
    for (std::size_t i = 0; i < nlines; ++i)
        w.initial.push_back((initial >> (i % 8)) & 1);

    for (const auto& o : info.options)
        if (o.key != "glitch_ns") req.options[o.key] = optionValue(o, in);
    static const char* kGlitch[] = {nullptr, "5", "100", "1e6"};
    if (const char* g = kGlitch[(flags >> 4) & 3]) req.options["glitch_ns"] = g;

    // Edges, within what readers hand on (lastTickOf: what an Edge holds, and times in ns
    // an int64 holds); decoders add timeouts to edge times.
    const Tick max_tick = lastTickOf(w.timebase);
    std::vector<std::uint8_t> level(w.initial);
    Tick t = start;
    while (!in.empty() && nlines > 0) {
        const std::uint8_t b = in.byte();
        const std::uint32_t line = std::uint32_t((b & 7) % nlines);
        const std::uint64_t d = deltaOf(b >> 5, in);
        t = (d >= std::uint64_t(max_tick - t)) ? max_tick : t + Tick(d);
        const std::uint8_t lv = (b & 8) ? ((b >> 4) & 1) : std::uint8_t(!level[line]);
        level[line] = lv;
        w.edges.push_back({t, line, lv});
    }
    w.start = start;
    w.end = t;

    decodeChecked(w, req, !((flags >> 6) & 1));
    checkBlocksMatchEdges(*factory, w, req, line_of_role);
    // Half the inputs: a VCD file written and decoded twice costs more than the rest.
    if ((flags >> 7) & 1) checkPiecesMatchInOrder(*factory, w, req);
}

DecodeStats decodeChecked(const Waveform& w, const DecoderRequest& req, bool reads_fields) {
    registerDecoders();
    std::unique_ptr<CaptureReader> reader = memoryReader(w);
    std::unique_ptr<Session> session;
    DecodeStats stats;
    try {
        session = std::make_unique<Session>(std::vector<DecoderRequest>{req}, *reader, "fuzz");
    } catch (const InputError&) {
        stats.refused = true;  // an option combination the decoder refuses up front: fine
        return stats;
    }
    CheckingSink sink;
    sink.requests = {req};
    sink.reads_fields = reads_fields;
    session->addSink(&sink);
    try {
        session->start();
    } catch (const InputError&) {
        stats.refused = true;  // a capture the decoder refuses before its first edge: fine
        return stats;
    }
    try {
        session->run();
    } catch (const HarnessFailure&) {
        throw;
    } catch (const std::exception& e) {
        failure(std::string("decoding threw: ") + e.what());
    }
    for (const auto& a : session->facts().advice)
        if (a.empty() || a.find('\n') != std::string::npos)
            failure(fmt::format("advice not a single line: '{}'", a));
    stats.edges = session->facts().edges;
    stats.events = sink.events;
    if (stats.events > 4 * stats.edges + 64)
        failure(fmt::format("{} events from {} edges", stats.events, stats.edges));
    return stats;
}

}  // namespace busdecode::fuzz

namespace busdecode::fuzz {

namespace {
void putVarint(std::string& out, std::uint64_t v) {
    do {
        std::uint8_t b = v & 0x7f;
        v >>= 7;
        if (v) b |= 0x80;
        out += char(b);
    } while (v);
}
}  // namespace

std::string encodeDecoderInput(const std::string& id, const Waveform& w,
                               const DecoderRequest& req) {
    registerDecoders();
    const DecoderFactory* factory = Registry::instance().find(id);
    if (!factory) throw HarnessFailure("decoder '" + id + "' is not built in");
    const DecoderInfo& info = factory->info();
    std::string out;
    std::size_t tb = 0;
    for (std::size_t i = 0; i < std::size(kTimebases); ++i)
        if (kTimebases[i].num == w.timebase.num && kTimebases[i].den == w.timebase.den) tb = i;
    out += char(tb);
    out += char(0);  // every role bound, no glitch filter
    // The waveform's lines are taken in role order: line k of `w` is role k.
    std::uint8_t initial = 0;
    for (std::size_t i = 0; i < w.initial.size() && i < 8; ++i)
        initial |= std::uint8_t(w.initial[i] << i);
    out += char(initial);
    putVarint(out, 0);  // start offset
    for (const auto& o : info.options) {
        if (o.key == "glitch_ns") continue;
        auto it = req.options.find(o.key);
        using K = OptionSpec::Kind;
        if (o.kind == K::Bool) {
            out += char(it != req.options.end() && it->second == "1");
        } else if (o.kind == K::Choice) {
            std::size_t k = 0;
            for (std::size_t c = 0; c < o.choices.size(); ++c)
                if (it != req.options.end() && o.choices[c] == it->second) k = c;
            if (it == req.options.end())
                for (std::size_t c = 0; c < o.choices.size(); ++c)
                    if (o.choices[c] == o.default_value) k = c;
            out += char(k);
        } else if (o.kind == K::String) {
        } else if (it == req.options.end() || it->second == "auto") {
            out += char(it == req.options.end() ? 0 : 5);
            out += char(0);
        } else {
            out += char(6);
            out += char(0);
            const double v = std::stod(it->second);
            if (o.kind == K::Int) {
                putVarint(out, std::uint64_t(std::int64_t(v)));
            } else {
                std::uint64_t bits;
                std::memcpy(&bits, &v, sizeof bits);
                putVarint(out, bits);
            }
        }
    }
    Tick t = w.start;
    for (const Edge& e : w.edges) {
        const std::uint64_t d = std::uint64_t(e.t - t);
        t = e.t;
        const int kind = d == 0 ? 0 : d < 256 ? 1 : 4;
        out += char((e.line & 7) | 8 | (e.level << 4) | (kind << 5));
        if (kind == 1) out += char(d);
        if (kind == 4) putVarint(out, d);
    }
    return out;
}

}  // namespace busdecode::fuzz
