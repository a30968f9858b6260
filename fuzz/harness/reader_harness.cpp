// Reader targets: the bytes become a file (an anonymous in-memory file, named by its
// /proc/self/fd path) read through openCapture with every signal selected, checking
// what the session relies on: edges in time order, levels 0/1, line indices in range,
// known_until never behind the last edge, an InputError naming the file for anything
// unreadable, and nothing else thrown.
#include <algorithm>

#include "byte_stream.h"
#include "capture/capture_reader.h"
#include "core/options.h"
#include "fuzz_harness.h"
#include "mem_file.h"
#include "reader_targets.h"
#include "zip_builder.h"

namespace busdecode::fuzz {

namespace {

[[noreturn]] void failure(const std::string& what) {
    throw HarnessFailure(what);
}

// Selects every scalar signal and a few bits of each vector (at most 64 lines), then
// reads the whole capture.
void readAll(CaptureReader& r) {
    std::vector<LineRef> lines;
    const auto& sigs = r.signals();
    for (int i = 0; i < int(sigs.size()) && lines.size() < 64; ++i) {
        if (sigs[i].width <= 1) {
            lines.push_back({i, -1});
        } else {
            lines.push_back({i, 0});
            lines.push_back({i, sigs[i].width - 1});
            if (sigs[i].width > 2) lines.push_back({i, sigs[i].width / 2});
        }
    }
    r.select(lines);
    const auto initial = r.initialLevels();
    if (initial.size() != lines.size()) failure("initialLevels() size differs from the selection");
    for (auto v : initial)
        if (v > 1) failure("initial level is neither 0 nor 1");
    const Tick start = r.startTick();
    Tick last = start;
    EdgeBlock block;
    std::uint64_t blocks = 0;
    while (r.next(block)) {
        ++blocks;
        if (block.edges.size() > kEdgeBlockSize) failure("block larger than kEdgeBlockSize");
        for (const Edge& e : block.edges) {
            if (e.line >= lines.size()) failure("edge on a line that was not selected");
            if (e.level > 1) failure("edge level is neither 0 nor 1");
            if (e.t < last) failure("edges out of time order (or before startTick)");
            last = e.t;
        }
        if (block.known_until != kNoTick && block.known_until < last)
            failure("known_until is behind the block's last edge");
        // A non-follow reader over a finite file hands out at least one edge per block
        // or ends: endless empty blocks would be a hang.
        if (block.edges.empty() && blocks > 1000000) failure("endless empty blocks");
    }
    if (r.endTick() < last) failure("endTick() is before the last edge");
}

void checkReader(const std::string& bytes, const OpenOptions& opts) {
    MemFile file(bytes);
    try {
        auto reader = openCapture(file.path(), opts);
        readAll(*reader);
    } catch (const InputError& e) {
        const std::string msg = e.what();
        if (msg.rfind(file.path(), 0) != 0)
            failure("input error does not start with the file name: " + msg);
        if (msg.find('\n') != std::string::npos) failure("input error is not one line: " + msg);
    } catch (const HarnessFailure&) {
        throw;
    } catch (const std::exception& e) {
        failure(std::string("exception that is not an InputError: ") + e.what());
    }
}

}  // namespace

void runReaderTarget(ReaderKind kind, const std::uint8_t* data, std::size_t size) {
    OpenOptions opts;
    std::string bytes(reinterpret_cast<const char*>(data), size);
    switch (kind) {
        case ReaderKind::Text:
            break;
        case ReaderKind::PlainCsv:
            opts.rate_hz = 1e6;  // plain CSV has no time column and needs --rate
            break;
        case ReaderKind::Sr:
            bytes = srFromFuzzBytes(data, size);
            break;
        case ReaderKind::Dsl:
            bytes = dslFromFuzzBytes(data, size);
            break;
    }
    checkReader(bytes, opts);
}

// Raw archives ("PK\3\4...") pass as they are; anything else is read as
//   metadata text, '\0', flags byte, then chunks of (varint length, bytes)
// and packed into a stored ZIP: `version` (flag bit 0), `metadata`, and the chunks as
// logic-1-1, logic-1-2, ... (flag bit 1: one old-style `logic-1`).
std::string srFromFuzzBytes(const std::uint8_t* data, std::size_t size) {
    std::string raw(reinterpret_cast<const char*>(data), size);
    if (raw.rfind("PK\x03\x04", 0) == 0) return raw;
    const auto nul = raw.find('\0');
    std::vector<std::pair<std::string, std::string>> entries;
    const std::string metadata = raw.substr(0, nul);
    ByteStream rest(data + std::min(size, nul == std::string::npos ? size : nul + 1),
                    nul == std::string::npos ? 0 : size - nul - 1);
    const std::uint8_t flags = rest.byte();
    if (!(flags & 1)) entries.push_back({"version", "2"});
    entries.push_back({"metadata", metadata});
    for (int k = 1; k <= 8 && !rest.empty(); ++k) {
        const std::size_t len = std::min<std::size_t>(rest.varint() % 65536, rest.left());
        std::string chunk;
        for (std::size_t i = 0; i < len; ++i)
            chunk += char(rest.byte());
        entries.push_back({(flags & 2) ? (k == 1 ? "logic-1" : "logic-1-" + std::to_string(k))
                                       : "logic-1-" + std::to_string(k),
                           chunk});
    }
    return buildStoredZip(entries);
}

}  // namespace busdecode::fuzz
