// Reader targets for the formats of other tools: DSView sessions built from structured
// bytes, compressed streams taken as they are, and row-per-sample text (ILA CSV, sample
// lists) read with a rate. All go through openCapture and the reader checks.
#include "byte_stream.h"
#include "reader_targets.h"
#include "zip_builder.h"

namespace busdecode::fuzz {

// Raw archives ("PK\3\4...") pass as they are; anything else is read as
//   header text, '\0', then members of (probe byte, block byte, varint length, bytes)
// packed into a stored ZIP as `header` and `L-<probe % 4>/<block % 4>` (a header saying
// `device mode = 1`: `O-<probe % 4>/0`; `device mode = 2`: `A-0/<block % 4>`).
namespace {

std::string memberName(const std::string& header, int probe, int block) {
    if (header.find("device mode = 1") != std::string::npos)
        return "O-" + std::to_string(probe) + "/0";
    if (header.find("device mode = 2") != std::string::npos) return "A-0/" + std::to_string(block);
    return "L-" + std::to_string(probe) + "/" + std::to_string(block);
}

}  // namespace

std::string dslFromFuzzBytes(const std::uint8_t* data, std::size_t size) {
    std::string raw(reinterpret_cast<const char*>(data), size);
    if (raw.rfind("PK\x03\x04", 0) == 0) return raw;
    const auto nul = raw.find('\0');
    std::vector<std::pair<std::string, std::string>> entries = {{"header", raw.substr(0, nul)}};
    ByteStream rest(data + std::min(size, nul == std::string::npos ? size : nul + 1),
                    nul == std::string::npos ? 0 : size - nul - 1);
    for (int k = 0; k < 8 && !rest.empty(); ++k) {
        const int probe = rest.byte() % 4, block = rest.byte() % 4;
        const std::size_t len = std::min<std::size_t>(rest.varint() % 65536, rest.left());
        std::string plane;
        for (std::size_t i = 0; i < len; ++i)
            plane += char(rest.byte());
        entries.push_back({memberName(entries[0].second, probe, block), plane});
    }
    return buildStoredZip(entries);
}

}  // namespace busdecode::fuzz
