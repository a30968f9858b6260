#include "decompressing_input.h"

#include <cerrno>
#include <csignal>
#include <cstring>
#include <vector>

#include <fcntl.h>
#include <lzma.h>
#include <pthread.h>
#include <unistd.h>
#include <zlib.h>
#include <zstd.h>

#include <fmt/format.h>

#include "core/options.h"

namespace busdecode {

Compression compressionOf(std::string_view head) {
    auto starts = [&](std::string_view magic) { return head.substr(0, magic.size()) == magic; };
    if (starts("\x1f\x8b")) return Compression::Gzip;
    if (starts(std::string_view("\xfd"
                                "7zXZ\0",
                                6)))
        return Compression::Xz;
    if (starts("\x28\xb5\x2f\xfd")) return Compression::Zstd;
    return Compression::None;
}

const char* compressionName(Compression c) {
    switch (c) {
        case Compression::Gzip:
            return "gzip";
        case Compression::Xz:
            return "xz";
        case Compression::Zstd:
            return "zstd";
        case Compression::CrLineEnds:
            return "cr-lines";
        case Compression::None:
            break;
    }
    return "none";
}

bool hasBareCrLineEnds(std::string_view head) {
    const std::size_t end = head.find_first_of("\r\n");
    return end != std::string_view::npos && head[end] == '\r' && end + 1 < head.size() &&
           head[end + 1] != '\n';
}

namespace {

struct StreamError {
    std::string what;
};

// One decompressor behind one interface: run() takes input and gives output; finish(),
// at the end of the input, gives what is left and says whether the stream ended whole.
class Codec {
public:
    virtual ~Codec() = default;
    // Decompresses from `in` (advanced past what it took) into out[0, cap): bytes written.
    virtual std::size_t run(std::string_view& in, char* out, std::size_t cap) = 0;
    virtual std::size_t finish(char* out, std::size_t cap, bool& whole) = 0;
};

class GzipCodec : public Codec {
public:
    GzipCodec() {
        if (inflateInit2(&z_, 15 + 32) != Z_OK) throw std::bad_alloc();  // gzip or zlib header
    }
    ~GzipCodec() override { inflateEnd(&z_); }
    std::size_t run(std::string_view& in, char* out, std::size_t cap) override {
        if (member_done_) {
            // Trailing zeros (padding) are ignored as gzip does; another member goes on.
            if (in.find_first_not_of('\0') == std::string_view::npos) {
                in = {};
                return 0;
            }
            inflateReset(&z_);
            member_done_ = false;
        }
        z_.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(in.data()));
        z_.avail_in = uInt(std::min<std::size_t>(in.size(), 1u << 30));
        z_.next_out = reinterpret_cast<Bytef*>(out);
        z_.avail_out = uInt(cap);
        const int rc = inflate(&z_, Z_NO_FLUSH);
        in.remove_prefix(std::size_t(reinterpret_cast<const char*>(z_.next_in) - in.data()));
        if (rc == Z_STREAM_END)
            member_done_ = true;
        else if (rc != Z_OK && rc != Z_BUF_ERROR)
            throw StreamError{fmt::format("corrupt gzip stream ({})", z_.msg ? z_.msg : "error")};
        return cap - z_.avail_out;
    }
    std::size_t finish(char*, std::size_t, bool& whole) override {
        whole = member_done_;
        return 0;
    }

private:
    z_stream z_{};
    bool member_done_ = false;
};

// liblzma has no message for its codes: these are what its documentation says of them.
std::string lzmaErrorText(lzma_ret rc) {
    switch (rc) {
        case LZMA_MEM_ERROR:
            return "out of memory";
        case LZMA_MEMLIMIT_ERROR:
            return "memory limit reached";
        case LZMA_FORMAT_ERROR:
            return "not in the xz format";
        case LZMA_OPTIONS_ERROR:
            return "unsupported compression options";
        case LZMA_DATA_ERROR:
            return "compressed data is corrupt";
        case LZMA_UNSUPPORTED_CHECK:
            return "unsupported integrity check";
        default:
            return fmt::format("liblzma error {}", int(rc));
    }
}

class XzCodec : public Codec {
public:
    XzCodec() {
        if (lzma_stream_decoder(&s_, UINT64_MAX, LZMA_CONCATENATED) != LZMA_OK)
            throw std::bad_alloc();
    }
    ~XzCodec() override { lzma_end(&s_); }
    std::size_t run(std::string_view& in, char* out, std::size_t cap) override {
        return code(in, out, cap, LZMA_RUN);
    }
    std::size_t finish(char* out, std::size_t cap, bool& whole) override {
        std::string_view none;
        const std::size_t n = code(none, out, cap, LZMA_FINISH);
        whole = ended_;
        return n;
    }

private:
    std::size_t code(std::string_view& in, char* out, std::size_t cap, lzma_action action) {
        s_.next_in = reinterpret_cast<const std::uint8_t*>(in.data());
        s_.avail_in = in.size();
        s_.next_out = reinterpret_cast<std::uint8_t*>(out);
        s_.avail_out = cap;
        const lzma_ret rc = lzma_code(&s_, action);
        in.remove_prefix(in.size() - s_.avail_in);
        if (rc == LZMA_STREAM_END)
            ended_ = true;
        else if (rc == LZMA_BUF_ERROR && action == LZMA_FINISH)
            ended_ = false;  // truncated: finish() says so
        else if (rc != LZMA_OK && rc != LZMA_BUF_ERROR)
            throw StreamError{fmt::format("corrupt xz stream ({})", lzmaErrorText(rc))};
        return cap - s_.avail_out;
    }
    lzma_stream s_ = LZMA_STREAM_INIT;
    bool ended_ = false;
};

class ZstdCodec : public Codec {
public:
    ZstdCodec() : d_(ZSTD_createDStream()) {
        if (!d_) throw std::bad_alloc();
    }
    ~ZstdCodec() override { ZSTD_freeDStream(d_); }
    std::size_t run(std::string_view& in, char* out, std::size_t cap) override {
        ZSTD_inBuffer ib{in.data(), in.size(), 0};
        ZSTD_outBuffer ob{out, cap, 0};
        const std::size_t rc = ZSTD_decompressStream(d_, &ob, &ib);
        in.remove_prefix(ib.pos);
        if (ZSTD_isError(rc))
            throw StreamError{fmt::format("corrupt zstd stream ({})", ZSTD_getErrorName(rc))};
        frame_done_ = rc == 0;
        return ob.pos;
    }
    std::size_t finish(char*, std::size_t, bool& whole) override {
        whole = frame_done_;
        return 0;
    }

private:
    ZSTD_DStream* d_;
    bool frame_done_ = false;
};

// Not a compression: every CR, or CR LF, becomes one LF, so that each line keeps its number.
class CrLineEndsCodec : public Codec {
public:
    std::size_t run(std::string_view& in, char* out, std::size_t cap) override {
        std::size_t n = 0, i = 0;
        for (; i < in.size() && n < cap; ++i) {
            const char c = in[i];
            if (c == '\n' && after_cr_) {
                after_cr_ = false;
                continue;
            }
            after_cr_ = c == '\r';
            out[n++] = after_cr_ ? '\n' : c;
        }
        in.remove_prefix(i);
        return n;
    }
    std::size_t finish(char*, std::size_t, bool& whole) override {
        whole = true;
        return 0;
    }

private:
    bool after_cr_ = false;  // the LF of a CR LF pair split over two reads is still dropped
};

std::unique_ptr<Codec> makeCodec(Compression kind) {
    switch (kind) {
        case Compression::Gzip:
            return std::make_unique<GzipCodec>();
        case Compression::Xz:
            return std::make_unique<XzCodec>();
        case Compression::Zstd:
            return std::make_unique<ZstdCodec>();
        case Compression::CrLineEnds:
            return std::make_unique<CrLineEndsCodec>();
        case Compression::None:
            break;
    }
    throw std::logic_error("makeCodec: no compression");
}

constexpr std::size_t kOutBlock = 256 << 10;

}  // namespace

DecompressingInput::DecompressingInput(std::unique_ptr<TextSource> raw, Compression kind,
                                       const OpenOptions& opts)
    : raw_(std::move(raw)), kind_(kind), opts_(opts), name_(raw_->name()) {
    raw_total_ = raw_->bytesTotal();
    raw_->keepReadsOnThisThread();  // decompressing is the slow part, not the read
    int fds[2];
    if (pipe2(fds, O_CLOEXEC) != 0)
        throw InputError(fmt::format("{}: cannot make a pipe: {}", name_, std::strerror(errno)));
    read_fd_ = fds[0];
    write_fd_ = fds[1];
    fcntl(write_fd_, F_SETPIPE_SZ, 1 << 20);  // fewer switches between the two threads
    thread_ = std::thread([this] { run(); });
}

DecompressingInput::~DecompressingInput() {
    if (read_fd_ >= 0) ::close(read_fd_);  // output() never called: the writer stops
    if (thread_.joinable()) thread_.join();
}

std::unique_ptr<TextSource> DecompressingInput::output() {
    OpenOptions o = opts_;
    o.follow = false;
    // A followed file stops where it is stopped: this thread then ends the text, which is
    // read to that end, not cut as an interrupted read.
    if (opts_.follow) o.stop = nullptr;
    const int fd = read_fd_;
    read_fd_ = -1;
    return std::make_unique<TextSource>(fd, name_, o);
}

void DecompressingInput::throwIfBroken() const {
    std::lock_guard<std::mutex> lock(mu_);
    if (!error_.empty()) throw InputError(error_);
}

void DecompressingInput::run() {
    // A reader that stops early closes its end: the write then fails with EPIPE, and
    // this thread ends, instead of the process getting SIGPIPE.
    sigset_t pipe_signal;
    sigemptyset(&pipe_signal);
    sigaddset(&pipe_signal, SIGPIPE);
    pthread_sigmask(SIG_BLOCK, &pipe_signal, nullptr);
    try {
        decompress();
    } catch (const StreamError& e) {
        std::lock_guard<std::mutex> lock(mu_);
        error_ = fmt::format("{}: {} at compressed byte {}", name_, e.what, at_);
    } catch (const std::exception& e) {
        std::lock_guard<std::mutex> lock(mu_);
        error_ = fmt::format("{}: {}", name_, e.what());
    }
    raw_.reset();
    ::close(write_fd_);  // after error_ is set: a reader that sees the end sees the error
}

std::string_view DecompressingInput::take() {
    for (;;) {
        std::string_view bytes;
        const auto st = raw_->nextBytes(bytes);
        if (st == TextSource::Status::Line) {
            raw_read_.fetch_add(bytes.size(), std::memory_order_relaxed);
            return bytes;
        }
        if (st == TextSource::Status::Eof) return {};
        raw_->waitForData(50);
    }
}

bool DecompressingInput::put(const char* p, std::size_t n) {
    while (n > 0) {
        const ssize_t w = ::write(write_fd_, p, n);
        if (w < 0 && errno == EINTR) continue;
        if (w <= 0) return false;  // EPIPE: the reader has stopped
        p += w;
        n -= std::size_t(w);
    }
    return true;
}

void DecompressingInput::decompress() {
    const auto codec = makeCodec(kind_);
    std::vector<char> out(kOutBlock);
    for (std::string_view in = take(); !in.empty(); in = take()) {
        std::size_t n;
        do {
            try {
                n = codec->run(in, out.data(), out.size());
            } catch (const StreamError&) {
                // A codec takes its input up to where it found the fault: that is where.
                at_ = raw_read_.load(std::memory_order_relaxed) - in.size();
                throw;
            }
            if (!put(out.data(), n)) return;
        } while (!in.empty() || n == out.size());
    }
    bool whole = false;
    std::size_t n;
    at_ = raw_read_.load(std::memory_order_relaxed);
    do {
        n = codec->finish(out.data(), out.size(), whole);
        if (!put(out.data(), n)) return;
    } while (n == out.size());
    if (!whole && !(opts_.stop && opts_.stop->load()))
        throw StreamError{fmt::format("truncated {} stream: it ends", compressionName(kind_))};
}

namespace {

class DecompressedReader : public CaptureReader {
public:
    DecompressedReader(std::unique_ptr<CaptureReader> inner,
                       std::shared_ptr<DecompressingInput> input)
        : input_(std::move(input)), inner_(std::move(inner)) {}
    const std::vector<SignalInfo>& signals() const override { return inner_->signals(); }
    Timebase timebase() const override { return inner_->timebase(); }
    std::string formatName() const override {
        return inner_->formatName() + "+" + compressionName(input_->kind());
    }
    void select(const std::vector<LineRef>& lines) override { inner_->select(lines); }
    std::vector<std::uint8_t> initialLevels() override {
        return guarded([&] { return inner_->initialLevels(); });
    }
    Tick startTick() const override { return inner_->startTick(); }
    bool next(EdgeBlock& block) override {
        const bool more = guarded([&] { return inner_->next(block); });
        if (!more) input_->throwIfBroken();
        return more;
    }
    Tick endTick() const override { return inner_->endTick(); }
    std::uint64_t bytesRead() const override { return input_->compressedRead(); }
    std::uint64_t bytesTotal() const override { return input_->compressedTotal(); }
    bool changesOnly() const override { return inner_->changesOnly(); }
    std::vector<std::string> notes() const override { return inner_->notes(); }
    bool readsVoltages() const override { return inner_->readsVoltages(); }
    bool endsAtLastChange() const override { return inner_->endsAtLastChange(); }
    bool readsAhead() const override { return inner_->readsAhead(); }

private:
    template <class F>
    auto guarded(F f) -> decltype(f()) {
        try {
            return f();
        } catch (const InputError&) {
            input_->throwIfBroken();
            throw;
        }
    }
    // Declared first, destroyed last: the reader closes the pipe before the join.
    std::shared_ptr<DecompressingInput> input_;
    std::unique_ptr<CaptureReader> inner_;
};

}  // namespace

std::unique_ptr<CaptureReader> decompressedReader(std::unique_ptr<CaptureReader> inner,
                                                  std::shared_ptr<DecompressingInput> input) {
    return std::make_unique<DecompressedReader>(std::move(inner), std::move(input));
}

}  // namespace busdecode
