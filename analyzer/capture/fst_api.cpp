// fstapi's fatal errors as exceptions (the shim's hooks), and the block-chain check that
// runs before fstapi reads a file: fstapi trusts every length it reads.
#include "fst_api.h"

#include <fcntl.h>
#include <unistd.h>
#include <zlib.h>

#include <cstdio>
#include <cstring>

#include <fmt/format.h>

#define BUSDECODE_FST_API_NO_REDIRECT
#include "core/options.h"
#include "fst_api_shim.h"
#include "fstapi.h"

namespace busdecode {

namespace {

// fstapi's last message on this thread, kept for the exception its exit(255) becomes.
struct MessageSink {
    char text[512] = {};
    std::FILE* file = nullptr;
    ~MessageSink() {
        if (file) std::fclose(file);
    }
};
thread_local MessageSink tls_messages;

constexpr std::uint64_t kHeaderBlockBytes = 329;  // the header block's length field
constexpr int kBlockHeader = 0, kBlockGzipWrapper = 254, kBlockUnfinished = 255;
constexpr std::uint64_t kWrappingLength = std::uint64_t(1) << 62;

std::uint64_t bigEndian64(const unsigned char* p) {
    std::uint64_t v = 0;
    for (int i = 0; i < 8; ++i)
        v = (v << 8) | p[i];
    return v;
}

// The bytes the block walk reads: the file itself, or the gzip stream inside a wrapper.
class BlockInput {
public:
    BlockInput(const std::string& path, const std::string& name) : name_(name) {
        fd_ = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
        if (fd_ < 0)
            throw InputError(fmt::format("{}: cannot open: {}", name, std::strerror(errno)));
    }
    ~BlockInput() {
        if (gz_) gzclose(gz_);
        if (fd_ >= 0) ::close(fd_);
    }
    BlockInput(const BlockInput&) = delete;
    BlockInput& operator=(const BlockInput&) = delete;

    // Reads on through gzip from byte `offset` of the file.
    void unwrapFrom(off_t offset) {
        if (::lseek(fd_, offset, SEEK_SET) != offset || !(gz_ = gzdopen(fd_, "rb")))
            throw InputError(fmt::format("{}: cannot read its gzip wrapper", name_));
        fd_ = -1;  // gzclose() closes it
        at_ = 0;
    }
    bool read(void* out, std::size_t n) {
        std::size_t got = 0;
        auto* p = static_cast<char*>(out);
        while (got < n) {
            const long r =
                gz_ ? gzread(gz_, p + got, unsigned(n - got)) : long(::read(fd_, p + got, n - got));
            if (r <= 0) break;
            got += std::size_t(r);
        }
        at_ += got;
        return got == n;
    }
    bool skip(std::uint64_t n) {
        char buf[65536];
        while (n > 0) {
            if (!gz_) {  // a file: seek, then check the size once at the end
                const off_t end = ::lseek(fd_, 0, SEEK_END);
                // Compared without at_ + n, which a corrupt length wraps round to a
                // position behind this block: the walk then went round for ever.
                if (end < 0 || at_ > std::uint64_t(end) || n > std::uint64_t(end) - at_)
                    return false;
                at_ += n;
                return ::lseek(fd_, off_t(at_), SEEK_SET) == off_t(at_);
            }
            const std::size_t step = std::size_t(std::min<std::uint64_t>(n, sizeof buf));
            if (!read(buf, step)) return false;
            n -= step;
        }
        return true;
    }
    std::uint64_t at() const { return at_; }

private:
    std::string name_;
    int fd_ = -1;
    gzFile gz_ = nullptr;
    std::uint64_t at_ = 0;
};

struct ChainFacts {
    bool header = false, geometry = false, hierarchy = false;
    std::vector<FstValueBlock> value_blocks;
};

bool isValueBlock(int type) {
    return type == FST_BL_VCDATA || type == FST_BL_VCDATA_DYN_ALIAS ||
           type == FST_BL_VCDATA_DYN_ALIAS2;
}

// A value block's first fields: its times and the memory fstapi takes to unpack it (it
// allocates that much before reading a byte of the block's contents).
FstValueBlock readValueBlockHead(BlockInput& in, const std::string& name, int n, std::uint64_t at,
                                 std::uint64_t length, const char* where) {
    unsigned char head[24];
    if (length < 8 + sizeof head || !in.read(head, sizeof head))
        throw InputError(
            fmt::format("{}: FST block {} at byte {}{}: a value-change block "
                        "too short for its times",
                        name, n, at, where));
    const std::uint64_t unpacked = bigEndian64(head + 16);
    if (unpacked > kFstBlockBudget)
        throw InputError(
            fmt::format("{}: FST block {} at byte {}{} needs {} MB to unpack, more "
                        "than the {} MB the FST reader allows (corrupt, or written "
                        "with blocks too large)",
                        name, n, at, where, (unpacked >> 20) + 1, kFstBlockBudget >> 20));
    return {n, at, bigEndian64(head), bigEndian64(head + 8)};
}

// Walks blocks until the end of `in`; returns what it saw. `where` names the stream.
ChainFacts walkBlocks(BlockInput& in, const std::string& name, const char* where) {
    ChainFacts facts;
    for (int n = 0;; ++n) {
        const std::uint64_t at = in.at();
        unsigned char type = 0, len[8];
        if (!in.read(&type, 1)) {
            if (n == 0) throw InputError(fmt::format("{}: empty FST file{}", name, where));
            return facts;
        }
        if (!in.read(len, 8))
            throw InputError(
                fmt::format("{}: FST block {} at byte {}{} ends inside its length "
                            "(truncated)",
                            name, n, at, where));
        const std::uint64_t length = bigEndian64(len);
        if (type == kBlockUnfinished) {
            if (n == 0)
                throw InputError(
                    fmt::format("{}: unfinished FST file (its writer never closed it)", name));
            // fstapi steps over a block still being written by its length: one that runs
            // past the end stops it, one of 2^62 or more wraps its position back for ever.
            if (length >= kWrappingLength)
                throw InputError(
                    fmt::format("{}: FST block {} at byte {}{}: an unfinished block "
                                "of {} bytes (corrupt)",
                                name, n, at, where, length));
            if (length < 8 || !in.skip(length - 8)) return facts;
            continue;
        }
        if ((type > FST_BL_VCDATA_DYN_ALIAS2 && type != kBlockGzipWrapper) || length < 8)
            throw InputError(
                fmt::format("{}: FST block {} at byte {}{}: type {} length {} is not "
                            "an FST block",
                            name, n, at, where, type, length));
        if (n == 0 && type != kBlockHeader)
            throw InputError(fmt::format("{}: FST file{} without its header block", name, where));
        if (type == kBlockHeader && (n != 0 || length != kHeaderBlockBytes))
            throw InputError(
                fmt::format("{}: FST block {} at byte {}{}: a header block of {} "
                            "bytes where only the first, of 329, belongs",
                            name, n, at, where, length));
        std::uint64_t read = 8;
        if (isValueBlock(type)) {
            facts.value_blocks.push_back(readValueBlockHead(in, name, n, at, length, where));
            read += 24;
        }
        if (!in.skip(length - read))
            throw InputError(
                fmt::format("{}: FST block {} at byte {}{} says {} bytes, the file "
                            "ends first (truncated)",
                            name, n, at, where, length));
        facts.header = facts.header || type == kBlockHeader;
        facts.geometry = facts.geometry || type == FST_BL_GEOM;
        facts.hierarchy = facts.hierarchy || type == FST_BL_HIER || type == FST_BL_HIER_LZ4 ||
                          type == FST_BL_HIER_LZ4DUO;
    }
}

}  // namespace

bool looksLikeFst(std::string_view head) {
    if (head.size() < 9) return false;
    const auto* u = reinterpret_cast<const unsigned char*>(head.data());
    if (u[0] == kBlockHeader || u[0] == kBlockUnfinished)
        return bigEndian64(u + 1) == kHeaderBlockBytes;
    return u[0] == kBlockGzipWrapper && head.size() >= 19 && u[17] == 0x1f && u[18] == 0x8b;
}

std::string FstBlockChain::blockAt(std::uint64_t time) const {
    for (const FstValueBlock& b : value_blocks)
        if (b.to >= time || &b == &value_blocks.back())
            return fmt::format("block {} at byte {}{}", b.number, b.at, where);
    return "value blocks" + where;
}

FstBlockChain checkFstBlocks(const std::string& path, const std::string& name) {
    BlockInput in(path, name);
    unsigned char first[17];
    const bool wrapped = in.read(first, 17) && first[0] == kBlockGzipWrapper;
    ChainFacts facts;
    if (wrapped) {
        const std::uint64_t length = bigEndian64(first + 1), unpacked = bigEndian64(first + 9);
        if (!in.skip(length - 16) || in.skip(1))
            throw InputError(fmt::format("{}: its gzip wrapper says {} bytes, the file holds {}",
                                         name, length + 1, in.at()));
        BlockInput inner(path, name);
        inner.unwrapFrom(17);
        facts = walkBlocks(inner, name, " (inside its gzip wrapper)");
        if (inner.at() != unpacked)
            throw InputError(
                fmt::format("{}: its gzip wrapper holds {} bytes, {} stated "
                            "(truncated or corrupt)",
                            name, inner.at(), unpacked));
    } else {
        BlockInput again(path, name);
        facts = walkBlocks(again, name, "");
    }
    if (!facts.geometry || !facts.hierarchy)
        throw InputError(fmt::format("{}: FST file without its {} block", name,
                                     facts.geometry ? "hierarchy" : "geometry"));
    return {std::move(facts.value_blocks), wrapped ? " (inside its gzip wrapper)" : ""};
}

void FstContextCloser::operator()(void* ctx) const {
    fstReaderClose(ctx);
}

}  // namespace busdecode

extern "C" FILE* busdecode_fst_messages(void) {
    auto& m = busdecode::tls_messages;
    if (!m.file) m.file = fmemopen(m.text, sizeof m.text - 1, "w");
    if (!m.file) return stderr;  // (no memory: the message goes where fstapi meant it)
    std::memset(m.text, 0, sizeof m.text);
    std::rewind(m.file);
    return m.file;
}

extern "C" int busdecode_fst_fgetc(FILE* f) {
    // Past this many EOFs in a row fstapi is looping over a corrupt hierarchy; a sound
    // file gives one at the end of each stream it reads.
    constexpr int kEofsInARow = 4096;
    thread_local FILE* eof_file = nullptr;
    thread_local int eofs = 0;
    const int c = std::fgetc(f);
    if (c != EOF) {
        eofs = 0;
        return c;
    }
    eofs = f == eof_file ? eofs + 1 : 1;
    eof_file = f;
    if (eofs > kEofsInARow) {
        eofs = 0;
        throw busdecode::FstApiFatal("fstapi: a stream ends inside an item (corrupt or truncated)");
    }
    return c;
}

extern "C" void busdecode_fst_fatal(int) {
    auto& m = busdecode::tls_messages;
    if (m.file) std::fflush(m.file);
    std::string text = m.text;
    if (text.rfind("FSTAPI  | ", 0) == 0) text.erase(0, 10);
    while (!text.empty() && (text.back() == '\n' || text.back() == '.'))
        text.pop_back();
    if (text.size() > 9 && text.ends_with(", exiting")) text.resize(text.size() - 9);
    throw busdecode::FstApiFatal(text.empty() ? "fstapi gave up" : "fstapi: " + text);
}
