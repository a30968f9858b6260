// openCapture: recognises the format by content, not by the file name: gzip, xz and zstd
// are decompressed and looked at again, a ZIP is a sigrok session, text starting with a
// `$keyword` is VCD, other text is CSV.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>

#include <fmt/format.h>
#include <unistd.h>

#include "core/options.h"
#include "core/utf8.h"
#include "decompressing_input.h"
#include "fst_api.h"
#include "readers.h"
#include "sample_rows_reader.h"
#include "zip_archive.h"

namespace busdecode {

std::string printable(std::string_view s, std::size_t max) {
    std::string out;
    const std::string text(s.substr(0, std::min(s.size(), max + 3)));  // a last sequence whole
    for (std::size_t i = 0; i < s.size() && i < max; ++i) {
        const auto u = static_cast<unsigned char>(s[i]);
        const std::size_t n = u >= 0x80 ? utf8SequenceLength(text, i) : 0;
        if (u >= 0x20 && u < 0x7f) {
            out += char(u);
        } else if (n > 0) {  // "µs", "∞", "mäx": as written, not as bytes
            out.append(text, i, n);
            i += n - 1;
        } else {
            out += fmt::format("\\x{:02x}", u);
        }
    }
    if (s.size() > max) out += "...";
    return out;
}

std::int64_t parseRateHz(std::string_view text) {
    auto isSp = [](char c) { return c == ' ' || c == '\t' || c == '\r'; };
    while (!text.empty() && isSp(text.front()))
        text.remove_prefix(1);
    while (!text.empty() && isSp(text.back()))
        text.remove_suffix(1);
    std::size_t i = 0;
    while (i < text.size() && ((text[i] >= '0' && text[i] <= '9') || text[i] == '.'))
        ++i;
    if (i == 0) return 0;
    const double v = std::strtod(std::string(text.substr(0, i)).c_str(), nullptr);
    std::string unit;
    for (char c : text.substr(i))
        if (!isSp(c)) unit += char(std::tolower(static_cast<unsigned char>(c)));
    double mul = 0;
    if (unit.empty() || unit == "hz")
        mul = 1;
    else if (unit == "khz")
        mul = 1e3;
    else if (unit == "mhz")
        mul = 1e6;
    else if (unit == "ghz")
        mul = 1e9;
    const double hz = v * mul;
    if (!(hz >= 1) || hz > 1e15) return 0;
    return std::int64_t(std::llround(hz));
}

namespace {

bool looksBinary(std::string_view head) {
    std::size_t odd = 0;
    for (char c : head) {
        const auto u = static_cast<unsigned char>(c);
        if (u == 0) return true;
        if (u < 0x20 && c != '\n' && c != '\r' && c != '\t' && c != '\f') ++odd;
    }
    return odd * 10 > head.size();  // a few stray control bytes are not enough
}

// A seekable, already unlinked copy of standard input (libzip needs to seek).
int copyToTempFile(TextSource& src) {
    std::string tmpl = (std::filesystem::temp_directory_path() / "busdecode-stdin-XXXXXX").string();
    int fd = mkstemp(tmpl.data());
    if (fd < 0)
        throw InputError(src.name() +
                         ": cannot create a temporary file for a .sr from standard input");
    unlink(tmpl.c_str());
    try {
        src.drainTo(fd);
    } catch (...) {
        close(fd);
        throw;
    }
    lseek(fd, 0, SEEK_SET);
    return fd;
}

}  // namespace

namespace {

std::unique_ptr<CaptureReader> openSource(std::unique_ptr<TextSource> src, const std::string& path,
                                          const OpenOptions& opts);

std::unique_ptr<CaptureReader> openCompressed(std::unique_ptr<TextSource> src, Compression kind,
                                              const OpenOptions& opts) {
    auto input = std::make_shared<DecompressingInput>(std::move(src), kind, opts);
    try {
        return decompressedReader(openSource(input->output(), "-", opts), input);
    } catch (const InputError&) {
        input->throwIfBroken();
        throw;
    }
}

// A sigrok session holds `metadata`, a DSView session `header`; a Saleae .sal (also a
// ZIP, `meta.json`) is undocumented and refused.
std::unique_ptr<CaptureReader> openZip(std::unique_ptr<TextSource> src, const std::string& path,
                                       const OpenOptions& opts) {
    const std::string name = src->name();
    // A pipe (standard input, a FIFO) is copied: a ZIP is read by offset.
    const bool by_path = path != "-" && std::filesystem::is_regular_file(path);
    const int fd = by_path ? -1 : copyToTempFile(*src);
    src.reset();
    auto zip = std::make_unique<ZipArchive>(by_path ? path : "-", fd, name,
                                            "ZIP capture (sigrok .sr or DSView .dsl)");
    if (zip->has("header") && !zip->has("metadata")) return openDsl(std::move(zip), opts);
    if (zip->has("meta.json") && !zip->has("metadata"))
        throw InputError(name +
                         ": a Saleae Logic 2 session (.sal): its format is undocumented and "
                         "changes between releases; export the channels as binary files in "
                         "Logic 2 (File > Export Data > Binary) and decode those");
    if (by_path) {
        if (auto analog = openSrAnalogIfAnalog(path, name, opts)) return analog;
    }
    return openSr(std::move(zip), opts);
}

// `path` is the file to reopen for formats read by offset (ZIP); "-" when there is none.
std::unique_ptr<CaptureReader> openSource(std::unique_ptr<TextSource> src, const std::string& path,
                                          const OpenOptions& opts) {
    std::string_view head = src->peek(4096);
    if (head.empty()) throw InputError(src->name() + ": empty file");
    if (const Compression kind = compressionOf(head); kind != Compression::None)
        return openCompressed(std::move(src), kind, opts);
    if (head.substr(0, 8) == "<SALEAE>") {
        if (path == "-")
            throw InputError(src->name() +
                             ": a Saleae binary export is read from its file (or folder), not "
                             "from a pipe");
        src.reset();
        return openSaleaeBin(path, opts);
    }
    if (looksLikeFst(head)) {  // fstapi reads a file by its path: a pipe is copied first
        const std::string name = src->name();
        if (path != "-" && std::filesystem::is_regular_file(path)) {
            src.reset();
            return openFst(path, name, opts);
        }
        const int fd = copyToTempFile(*src);
        src.reset();
        return openFst("/proc/self/fd/" + std::to_string(fd), name, opts, fd);
    }
    if (head.size() >= 4 && head.substr(0, 4) == std::string_view("PK\x03\x04", 4))
        return openZip(std::move(src), path, opts);
    std::string_view text = head;
    while (!text.empty() && (text.front() == ' ' || text.front() == '\t' || text.front() == '\r' ||
                             text.front() == '\n'))
        text.remove_prefix(1);
    if (text.empty() && head.size() < 4096)
        throw InputError(src->name() + ": empty file (only blank lines)");
    if (looksBinary(head))
        throw InputError(
            src->name() +
            ": unknown format: binary data that is neither VCD, CSV nor a sigrok .sr session");
    if (!text.empty() && text.front() == '$') return openVcd(std::move(src), opts);
    if (hasBareCrLineEnds(head))
        return openCompressed(std::move(src), Compression::CrLineEnds, opts);
    if (auto r = openIlaCsv(src, head, opts)) return r;
    if (auto r = openSampleList(src, head, opts)) return r;
    if (auto scope = openScopeCsvIfScope(src, opts)) return scope;
    return openCsv(std::move(src), opts);
}

}  // namespace

std::unique_ptr<CaptureReader> openCapture(const std::string& path, const OpenOptions& opts) {
    // A folder of one-file-per-channel exports (Saleae Logic 2) is one capture.
    if (path != "-" && std::filesystem::is_directory(path)) return openSaleaeBin(path, opts);
    return openSource(std::make_unique<TextSource>(path, opts), path, opts);
}

}  // namespace busdecode
