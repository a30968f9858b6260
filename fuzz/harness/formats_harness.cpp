// Reader targets for the formats of other tools: DSView sessions built from structured
// bytes, compressed streams taken as they are, and row-per-sample text (ILA CSV, sample
// lists) read with a rate. All go through openCapture and the reader checks.
#include "byte_stream.h"
#include "reader_targets.h"
#include "zip_builder.h"

namespace busdecode::fuzz {

// Raw archives ("PK\3\4...") pass as they are; anything else is read as
//   header text, '\0', then members of (probe byte, block byte, varint length, bytes)
// packed into a stored ZIP as `header` and `L-<probe % 4>/<block % 4>`.
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
        entries.push_back({"L-" + std::to_string(probe) + "/" + std::to_string(block), plane});
    }
    return buildStoredZip(entries);
}

}  // namespace busdecode::fuzz
