#include "support/feed/direct_feed.h"

#include <algorithm>
#include <cstdint>
#include <memory>

#include "core/block_decoding.h"
#include "sinks/event_format.h"

namespace busdecode {

namespace {

struct JsonLines : EventSink {
    explicit JsonLines(Timebase tb) : tb(tb) {}
    void onEvent(Event&& e) override {
        std::string line;
        appendEventJson(line, e, tb);
        lines.push_back(std::move(line));
    }
    Timebase tb;
    std::vector<std::string> lines;
};

}  // namespace

std::vector<std::string> decodeDirectly(const DecoderFactory& factory, const Options& options,
                                        const Waveform& w, const std::vector<int>& line_of_role,
                                        Feed feed, std::size_t block) {
    std::vector<int> role_of_line(w.names.size(), -1);
    for (std::size_t r = 0; r < line_of_role.size(); ++r)
        if (line_of_role[r] >= 0) role_of_line[std::size_t(line_of_role[r])] = int(r);
    std::vector<Edge> edges;
    std::vector<std::uint8_t> level(w.initial);
    for (const Edge& e : w.edges) {
        if (role_of_line[e.line] < 0 || level[e.line] == e.level) continue;
        level[e.line] = e.level;
        edges.push_back(e);
    }

    std::unique_ptr<Decoder> decoder = factory.create(options);
    JsonLines sink(w.timebase);
    DecoderContext ctx;
    ctx.timebase = w.timebase;
    ctx.sink = &sink;
    ctx.capture_start = w.start;
    for (const int line : line_of_role)
        ctx.initial_levels.push_back(line < 0 ? -1 : w.initial[std::size_t(line)]);
    FastDecoder* fast = fastPathOf(*decoder);
    if (fast) fast->setHints({true, linesAreRoles(role_of_line)});
    decoder->start(ctx);
    switch (feed) {
        case Feed::Reference:
            for (const Edge& e : edges)
                if (fast)
                    fast->edgeReference(e.t, role_of_line[e.line], e.level != 0);
                else
                    decoder->edge(e.t, role_of_line[e.line], e.level != 0);
            break;
        case Feed::OneByOne:
            for (const Edge& e : edges)
                decoder->edge(e.t, role_of_line[e.line], e.level != 0);
            break;
        case Feed::Blocks:
            block = std::max<std::size_t>(block, 1);
            for (std::size_t i = 0; i < edges.size(); i += block)
                feedEdges(*decoder, fast, edges.data() + i,
                          edges.data() + std::min(i + block, edges.size()), role_of_line.data());
            break;
    }
    decoder->finish(w.end);
    for (const auto& a : decoder->advice())
        sink.lines.push_back("advice: " + a);
    return sink.lines;
}

}  // namespace busdecode
