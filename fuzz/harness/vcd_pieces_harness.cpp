#include "vcd_pieces.h"

#include <fmt/format.h>

#include <functional>
#include <memory>
#include <vector>

#include "capture/capture_reader.h"
#include "core/options.h"
#include "fuzz_harness.h"
#include "mem_file.h"

namespace busdecode::fuzz {

OpenOptions sequentialOptions() {
    OpenOptions o;
    o.read_ahead = false;
    o.read_file_ahead = false;
    return o;
}

namespace {

std::string reading(const std::function<std::unique_ptr<CaptureReader>()>& open,
                    const std::function<void()>& before_edges = {}) {
    std::string out;
    try {
        std::unique_ptr<CaptureReader> r = open();
        std::vector<LineRef> lines;
        const auto& sigs = r->signals();
        for (int i = 0; i < int(sigs.size()) && lines.size() < 64; ++i) {
            if (sigs[i].width <= 1) {
                lines.push_back({i, -1});
            } else {
                lines.push_back({i, 0});
                lines.push_back({i, sigs[i].width / 2});
                lines.push_back({i, sigs[i].width - 1});
            }
        }
        r->select(lines);
        out += "initial ";
        for (std::uint8_t l : r->initialLevels())
            out += char('0' + l);
        out += fmt::format(" from {}\n", r->startTick());
        if (before_edges) before_edges();
        EdgeBlock block;
        while (r->next(block)) {
            for (const Edge& e : block.edges)
                out += fmt::format("{} {} {}\n", Tick(e.t), unsigned(e.line), unsigned(e.level));
            if (!block.edges.empty() && block.known_until < block.edges.back().t)
                out += "known_until before the block's last edge\n";
        }
        out += fmt::format("end {} bytes {}\n", r->endTick(), r->bytesRead());
    } catch (const InputError& e) {
        out += fmt::format("error {}\n", e.what());
    }
    return out;
}

}  // namespace

std::string sequentialVcdReading(const std::string& path) {
    return reading([&] { return openCapture(path, sequentialOptions()); });
}

std::string piecesVcdReading(const std::string& path, std::uint64_t piece_bytes,
                             std::uint64_t boundary_search,
                             const std::function<void()>& before_edges) {
    OpenOptions pieces;  // decode's: read ahead (in pieces, for a VCD file)
    pieces.vcd_piece_bytes = piece_bytes;
    pieces.vcd_boundary_search = boundary_search;
    return reading([&] { return openCapture(path, pieces); }, before_edges);
}

std::string readingDifference(const std::string& got, const std::string& want) {
    const auto want_error = want.rfind("error ");
    if (want_error == std::string::npos)
        return got == want ? "" : "the readings differ:\n" + want + "---\n" + got;
    const auto got_error = got.rfind("error ");
    if (got_error == std::string::npos) return "no error where there is one:\n" + got;
    if (got.substr(got_error) != want.substr(want_error))
        return "another error: " + got.substr(got_error) + " for " + want.substr(want_error);
    const std::size_t common = std::min(got_error, want_error);
    if (got.compare(0, common, want, 0, common) != 0)
        return "the edges before the error differ:\n" + want + "---\n" + got;
    return "";
}

void runVcdPiecesTarget(const std::uint8_t* data, std::size_t size) {
    if (size < 2) return;
    const std::uint64_t piece = 1 + data[0] % 64;
    const std::uint64_t search = data[1] >= 128 ? 65536 : 1 + data[1] % 64;
    const MemFile file(std::string(reinterpret_cast<const char*>(data) + 2, size - 2));
    const std::string difference = readingDifference(piecesVcdReading(file.path(), piece, search),
                                                     sequentialVcdReading(file.path()));
    if (!difference.empty())
        throw HarnessFailure(
            fmt::format("in pieces of {} bytes, search {}: {}", piece, search, difference));
}

}  // namespace busdecode::fuzz
