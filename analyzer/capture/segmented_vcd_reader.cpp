#include "segmented_vcd_reader.h"

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <condition_variable>
#include <cstring>
#include <mutex>
#include <thread>
#include <utility>
#include <vector>

#include <pthread.h>
#include <sys/stat.h>
#include <unistd.h>

#include "guarded_mapping.h"
#include "piece_work.h"

namespace busdecode {

namespace {

// One piece of the value changes: its bytes, and what tokenising them gave.
struct Piece {
    enum class State { Free, Working, Done };
    State state = State::Free;
    std::uint64_t index = 0;
    // Its bytes from file offset text_offset: mapped (GuardedMapping), or where the file
    // cannot be mapped, copied into `copy`.
    const char* text = nullptr;
    std::uint64_t text_offset = 0;
    GuardedMapping mapping;
    bool mapped = false;  // text is the mapping's
    std::unique_ptr<char[]> copy;
    std::size_t copy_capacity = 0;
    std::uint64_t begin = 0, end = 0;  // the piece: file offsets [begin, end)
    bool ok = false;                   // bounds found, tokenised without a fault
    VcdTokenState run;
    std::vector<EdgeBlock> blocks;
    std::size_t used = 0;  // blocks[0, used) hold its edges
    // Each thread tokenises into storage of its own: `blocks` and `copy` are thread
    // blocks_owner's, `other_blocks` and `other_copy` the other's (work() swaps them).
    // A cache line written on one core and then overwritten on the other must cross
    // between them, and on a VM whose two cores may sit on two dies that is slow: the
    // tokeniser ran 2.4 times as long (bench/README.md, "Two dies").
    std::vector<EdgeBlock> other_blocks;
    std::unique_ptr<char[]> other_copy;
    std::size_t other_copy_capacity = 0;
    int blocks_owner = 0;
    // Per line, where its first edge is (block * kEdgeBlockSize + index), or kNoEdge.
    std::vector<std::uint32_t> first_edge;
    // What the piece work (setPieceWork()) made of it, if anything.
    std::unique_ptr<PieceWork::Result> result;
};
constexpr std::uint32_t kNoEdge = PieceWork::kNoEdge;

class SegmentedVcdReader final : public CaptureReader, public PieceReader {
public:
    SegmentedVcdReader(std::unique_ptr<VcdTokeniser> vcd, std::uint64_t size,
                       std::uint64_t piece_bytes, std::uint64_t boundary_search)
        : vcd_(std::move(vcd)),
          size_(size),
          piece_bytes_(std::max<std::uint64_t>(piece_bytes, 1)),
          search_(std::max<std::uint64_t>(boundary_search, 1)),
          pieces_(kPiecesAhead) {}
    ~SegmentedVcdReader() override { stopHelper(); }

    const std::vector<SignalInfo>& signals() const override { return vcd_->signals(); }
    Timebase timebase() const override { return vcd_->timebase(); }
    std::string formatName() const override { return vcd_->formatName(); }
    std::string wallClockStart() const override { return vcd_->wallClockStart(); }
    void select(const std::vector<LineRef>& lines) override { vcd_->select(lines); }
    std::vector<std::uint8_t> initialLevels() override {
        auto levels = vcd_->initialLevels();
        if (!planned_) plan();
        return levels;
    }
    Tick startTick() const override { return vcd_->startTick(); }

    bool next(EdgeBlock& block) override {
        if (!planned_) initialLevels();
        if (sequential_) return vcd_->next(block);
        for (;;) {
            if (head_open_) {
                Piece& h = slot(head_);
                // The block handed out last goes back to its piece, and `block` gets its
                // own storage back: the storage stays with the thread that writes it.
                if (lent_) {
                    std::swap(block, h.blocks[handing_ - 1]);
                    lent_ = false;
                }
                while (handing_ < h.used) {
                    EdgeBlock& b = h.blocks[handing_++];
                    if (b.edges.empty()) continue;  // its one edge dropped (accept())
                    std::swap(block, b);
                    lent_ = true;
                    return true;
                }
                release();
            }
            if (head_ == count_) {
                block.clear();
                end_ = x_.seen_time ? x_.cur : vcd_->startTick();
                vcd_->finishedAt(x_);
                return false;
            }
            if (!awaitHead()) {
                fallBack();
                return vcd_->next(block);
            }
            head_open_ = true;
            handing_ = 0;
        }
    }
    std::vector<std::string> notes() const override { return vcd_->notes(); }
    Tick endTick() const override { return sequential_ ? vcd_->endTick() : end_; }
    std::uint64_t bytesRead() const override {
        return sequential_ ? vcd_->bytesRead() : expected_begin_;
    }
    std::uint64_t bytesTotal() const override { return size_; }
    bool changesOnly() const override { return true; }
    bool readsAhead() const override { return true; }
    bool setPieceWork(std::shared_ptr<PieceWork> work) override {
        if (!planned_) initialLevels();
        if (sequential_ || helper_.joinable()) return false;
        piece_work_ = std::move(work);
        return true;
    }
    std::unique_ptr<PieceWork::Result> takePieceResult(std::uint32_t& dropped) override {
        if (!head_result_) return nullptr;
        dropped = head_dropped_;
        return std::move(head_result_);
    }

private:
    Piece& slot(std::uint64_t k) { return pieces_[std::size_t(k % pieces_.size())]; }

    // After the initial levels: where the pieces start, how many there are, their state.
    void plan() {
        planned_ = true;
        const std::uint64_t at = vcd_->resumeOffset();
        if (at == VcdTokeniser::kNoOffset || at >= size_) {
            sequential_ = true;  // nothing left to cut, or not known where to
            return;
        }
        start_ = expected_begin_ = at;
        x_ = initial_ = vcd_->resumeState();
        count_ = (size_ - at + piece_bytes_ - 1) / piece_bytes_;
        main_tok_ = vcd_->clone();
        helper_tok_ = vcd_->clone();
        lines_ = x_.level.size();
    }

    bool claimable() const { return next_claim_ < count_ && next_claim_ < head_ + pieces_.size(); }

    // Claims the next piece (claimable(), `lock` held) and tokenises it with `tok`, the
    // lock released meanwhile, on `thread` (0: the decoding thread; 1: the helper).
    // Returns its index.
    std::uint64_t tokeniseNext(std::unique_lock<std::mutex>& lock, VcdTokeniser& tok, int thread) {
        const std::uint64_t k = next_claim_++;
        Piece& p = slot(k);
        p.state = Piece::State::Working;
        lock.unlock();
        work(k, tok, thread, p);
        lock.lock();
        p.state = Piece::State::Done;
        return k;
    }

    // Waits for the head piece, tokenising pieces ahead meanwhile, and completes it with
    // the state before it. False: it cannot be completed (read on sequentially).
    bool awaitHead() {
        std::unique_lock<std::mutex> lock(m_);
        if (!helper_.joinable() && !quit_) helper_ = std::thread([this] { help(); });
        Piece& h = slot(head_);
        while (!(h.state == Piece::State::Done && h.index == head_)) {
            if (claimable()) {
                tokeniseNext(lock, *main_tok_, 0);
                continue;
            }
            consumer_waiting_ = true;
            ready_.wait(lock);
            consumer_waiting_ = false;
        }
        lock.unlock();
        return accept(h);
    }

    // The helper thread: tokenises the pieces ahead, up to kPiecesAhead.
    void help() {
        // Named as the reading thread always was: top -H and perf tell the threads apart.
        pthread_setname_np(pthread_self(), "decode-read");
        std::unique_lock<std::mutex> lock(m_);
        for (;;) {
            if (quit_) return;
            if (!claimable()) {
                helper_waiting_ = true;
                space_.wait(lock);
                helper_waiting_ = false;
                continue;
            }
            const std::uint64_t k = tokeniseNext(lock, *helper_tok_, 1);
            if (consumer_waiting_ && k == head_) ready_.notify_one();
        }
    }

    // Frees the head piece's slot for a piece ahead.
    void release() {
        head_open_ = false;
        std::unique_lock<std::mutex> lock(m_);
        slot(head_).state = Piece::State::Free;
        ++head_;
        // A helper waiting for room is woken when half the slots are free, not at every
        // one: fewer wake-ups on the decoding thread when it is the slower one.
        const bool wake =
            helper_waiting_ && head_ + pieces_.size() >= next_claim_ + pieces_.size() / 2;
        lock.unlock();
        if (wake) space_.notify_one();
    }

    void stopHelper() {
        {
            std::lock_guard<std::mutex> lock(m_);
            quit_ = true;
        }
        space_.notify_all();
        if (helper_.joinable()) helper_.join();
    }

    // The rest of the file sequentially, from the head piece's start, in the state the
    // pieces before it left.
    void fallBack() {
        stopHelper();
        sequential_ = true;
        vcd_->resumeAt(expected_begin_, x_);
    }

    // Makes bytes [from, to) of the file the piece's text: mapped, or else copied. False
    // on a read error or a file that shrank (the sequential reader then reports what it
    // finds); a mapped file that shrinks is found out after the piece is read (shrunk_).
    bool readText(Piece& p, std::uint64_t from, std::uint64_t to) {
        p.text_offset = from;
        p.mapped = p.mapping.map(vcd_->fileDescriptor(), from, to, &shrunk_);
        if (p.mapped) {
            p.text = p.mapping.data();
            return true;
        }
        const std::size_t n = std::size_t(to - from);
        if (p.copy_capacity < n) {
            p.copy.reset(new char[n]);
            p.copy_capacity = n;
        }
        p.text = p.copy.get();
        std::size_t got = 0;
        while (got < n) {
            const ssize_t r =
                ::pread(vcd_->fileDescriptor(), p.copy.get() + got, n - got, off_t(from + got));
            if (r < 0 && errno == EINTR) continue;
            if (r <= 0) return false;
            got += std::size_t(r);
        }
        return true;
    }

    bool fileShrank() const {
        struct stat st;
        return ::fstat(vcd_->fileDescriptor(), &st) != 0 || std::uint64_t(st.st_size) < size_;
    }

    // The byte at file offset `off` in the piece's buffer (or just past its end).
    static const char* at(const Piece& p, std::uint64_t off) {
        return p.text + (off - p.text_offset);
    }

    // The first `#time` line starting at or after `x` and before x + search_ (the file's
    // end if that comes first and has none): where the pieces cut at x meet. kNoOffset if
    // there is none in reach.
    std::uint64_t boundary(const Piece& p, std::uint64_t x) const {
        if (x >= size_) return size_;
        const std::uint64_t stop = std::min(x + search_, size_);
        for (std::uint64_t i = x; i < stop; ++i) {
            const char* nl =
                static_cast<const char*>(std::memchr(at(p, i - 1), '\n', stop - i + 1));
            if (!nl) break;
            i = p.text_offset + std::uint64_t(nl - p.text) + 1;
            if (i < stop && *at(p, i) == '#') return i;
        }
        return stop == size_ ? size_ : VcdTokeniser::kNoOffset;
    }

    // Reads and tokenises piece k (any thread; no lock held). The first piece goes on
    // from the initial levels' state; the others start from nothing known.
    void work(std::uint64_t k, VcdTokeniser& tok, int thread, Piece& p) {
        if (p.blocks_owner != thread) {
            std::swap(p.blocks, p.other_blocks);
            std::swap(p.copy, p.other_copy);
            std::swap(p.copy_capacity, p.other_copy_capacity);
            p.blocks_owner = thread;
        }
        p.index = k;
        p.ok = false;
        p.used = 0;
        p.result.reset();
        const std::uint64_t x0 = start_ + k * piece_bytes_;
        const std::uint64_t x1 = std::min(start_ + (k + 1) * piece_bytes_, size_);
        // From the byte before x0 (is x0 a line start?) to the end of both searches.
        const std::uint64_t from = k == 0 ? x0 : x0 - 1;
        const std::uint64_t to = std::min(std::max(x0, x1) + search_, size_);
        try {
            if (!readText(p, from, to)) return;
            p.begin = k == 0 ? x0 : boundary(p, x0);
            p.end = boundary(p, x1);
            if (p.begin == VcdTokeniser::kNoOffset || p.end == VcdTokeniser::kNoOffset) return;
            if (k == 0) {
                p.run = initial_;  // the exact state: no fix-up
            } else {
                p.run.level.assign(lines_, kUnknownLevel);
                p.run.cur = 0;
                p.run.seen_time = false;
                p.run.in_block = false;
                p.run.line = 0;
                p.run.unknown_states = 0;
            }
            p.run.first_time = kNoTick;
            tok.tokenise(at(p, p.begin), at(p, p.end), p.run, p.blocks, p.used);
            if (k > 0) findFirstEdges(p);
            // Zeros read where the file shrank under its mapping decide nothing either:
            // past its new end (SIGBUS, shrunk_) or in the page that holds that end (no
            // fault). The tokeniser refuses NUL bytes anywhere, so that piece already
            // fails; the file's size, asked after the piece was read, does not rest on it.
            p.ok = !shrunk_.load(std::memory_order_seq_cst) && !(p.mapped && fileShrank());
        } catch (...) {
            // A fault in the traffic (InputError) or no memory: the sequential reader,
            // reading the same bytes on the decoding thread, meets it again and reports it.
            p.ok = false;
        }
        // The first piece is decoded from the capture's start anyway: no work ahead.
        if (p.ok && k > 0 && piece_work_) {
            try {
                p.result = piece_work_->run({p.blocks.data(), p.used, &p.first_edge, thread});
            } catch (...) {
                p.result.reset();  // nothing ahead for this piece: it is decoded as it comes
            }
        }
    }

    // Where each line's first edge in the piece is: the edges accept() may drop.
    void findFirstEdges(Piece& p) {
        p.first_edge.assign(lines_, kNoEdge);
        std::size_t left = 0;
        for (std::uint8_t l : p.run.level)
            left += l != kUnknownLevel;
        for (std::size_t b = 0; b < p.used && left > 0; ++b) {
            const auto& edges = p.blocks[b].edges;
            for (std::size_t i = 0; i < edges.size(); ++i) {
                std::uint32_t& first = p.first_edge[edges[i].line];
                if (first != kNoEdge) continue;
                first = std::uint32_t(b * kEdgeBlockSize + i);
                if (--left == 0) break;
            }
        }
    }

    // Completes the head piece with the state before it (x_), and moves x_ past it.
    bool accept(Piece& p) {
        if (!p.ok || p.begin != expected_begin_) return false;
        head_result_.reset();
        head_dropped_ = 0;
        if (p.index == 0) {
            x_ = p.run;
        } else {
            if (x_.in_block) return false;  // the piece's start was inside a $comment
            if (p.run.seen_time && p.run.first_time < x_.cur) return false;  // backwards
            // A first change to the level the line had is not an edge.
            std::vector<std::uint32_t> drop;
            for (std::size_t l = 0; l < lines_; ++l) {
                const std::uint32_t at = p.first_edge[l];
                if (at == kNoEdge) continue;
                const Edge& e = p.blocks[at / kEdgeBlockSize].edges[at % kEdgeBlockSize];
                if (e.level == x_.level[l]) drop.push_back(at);
            }
            std::sort(drop.rbegin(), drop.rend());
            head_dropped_ = std::uint32_t(drop.size());
            head_result_ = std::move(p.result);
            for (std::uint32_t at : drop) {
                auto& edges = p.blocks[at / kEdgeBlockSize].edges;
                edges.erase(edges.begin() + std::ptrdiff_t(at % kEdgeBlockSize));
            }
            for (std::size_t l = 0; l < lines_; ++l)
                if (p.run.level[l] != kUnknownLevel) x_.level[l] = p.run.level[l];
            if (p.run.seen_time) {
                x_.cur = p.run.cur;
                x_.seen_time = true;
            }
            x_.in_block = p.run.in_block;
            x_.line += p.run.line;
            x_.unknown_states += p.run.unknown_states;
        }
        expected_begin_ = p.end;
        return true;
    }

    std::unique_ptr<VcdTokeniser> vcd_;  // header, initial levels, and the fallback
    const std::uint64_t size_;
    const std::uint64_t piece_bytes_;
    const std::uint64_t search_;
    bool planned_ = false;
    bool sequential_ = false;  // next() is vcd_'s
    std::uint64_t start_ = 0;  // where piece 0 starts
    std::uint64_t count_ = 0;  // pieces
    std::size_t lines_ = 0;
    std::unique_ptr<VcdTokeniser> main_tok_, helper_tok_;
    VcdTokenState initial_;  // where piece 0 starts (read by either thread)

    // The decoding thread's: the state after the pieces handed out, and the head piece.
    VcdTokenState x_;
    std::uint64_t expected_begin_ = 0;  // where the head piece must start
    bool head_open_ = false;            // the head piece is being handed out
    bool lent_ = false;                 // next()'s block is the head's block handing_ - 1
    std::size_t handing_ = 0;           // its next block
    Tick end_ = 0;
    std::shared_ptr<PieceWork> piece_work_;  // set before the helper starts, then only read
    // The head piece's result, until takePieceResult() takes it, and its dropped edges.
    std::unique_ptr<PieceWork::Result> head_result_;
    std::uint32_t head_dropped_ = 0;

    // Set when a read of a piece's mapping found the file shorter than it was (declared
    // before the pieces, whose mappings point at it).
    std::atomic<bool> shrunk_{false};
    std::vector<Piece> pieces_;  // piece k in pieces_[k % kPiecesAhead]
    std::mutex m_;
    std::condition_variable ready_, space_;
    std::uint64_t head_ = 0;        // the piece being decoded (or next to be)
    std::uint64_t next_claim_ = 0;  // the next piece to tokenise
    bool quit_ = false;
    bool helper_waiting_ = false;
    bool consumer_waiting_ = false;
    std::thread helper_;
};

}  // namespace

std::unique_ptr<CaptureReader> segmentedVcdReader(std::unique_ptr<VcdTokeniser> vcd,
                                                  std::uint64_t file_size,
                                                  std::uint64_t piece_bytes,
                                                  std::uint64_t boundary_search) {
    return std::make_unique<SegmentedVcdReader>(std::move(vcd), file_size, piece_bytes,
                                                boundary_search);
}

}  // namespace busdecode
