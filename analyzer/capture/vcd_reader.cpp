// VCD reader: a byte-level scan of the value-change section, one line at a time,
// without a std::string or an allocation per change.
//
// Dialect notes (what a user can rely on):
// - `$timescale` 1/10/100 of s, ms, us, ns, ps, fs, written `1ns`, `1 ns` or across
//   lines; without one the unit is 1 ns. One tick = one timescale unit.
// - Nested `$scope`s make full_name `a.b.sig`; name is the last component. A vector's
//   range (`data [7:0]`) is not part of its name; a 1-bit `$var` keeps an index in its
//   reference (`bus[3]`) so it can be mapped by that name.
// - Identifier codes of any length; several `$var`s may share one code (aliases).
// - Several changes may follow a timestamp on its line (`#0 1! 1"`, as sigrok writes).
// - `$dumpvars/$dumpon/$dumpoff/$dumpall` and `$end` are transparent; `$comment` (and
//   any other keyword block) is skipped up to its `$end`, on the same or a later line.
// - States: IEEE 1364/1800 `0 1 x z` and VHDL's (GHDL, NVC) `U X 0 1 Z W L H -`, in
//   either case. L and H (weak) are levels 0 and 1; x, z, u, w and - are not levels: a
//   line keeps its previous level through them; before any known level it reads 1 (the
//   idle level of most buses). The same holds per bit of a vector. A selected real reads
//   1 when nonzero.
// - Bit k of a vector (LineRef::bit) counts from the LSB; a value shorter than the
//   vector is extended the VCD way (0 for a leading 1 or 0, else the leading x/z).
// - Initial levels are those at the first timestamp (including `$dumpvars` before it);
//   startTick is the first timestamp, endTick the last one.
#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cstring>
#include <memory>
#include <optional>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "core/options.h"
#include "core/own_cache_lines.h"
#include "core/sample_rate.h"
#include "decimal_scan.h"
#include "readers.h"
#include "segmented_vcd_reader.h"
#include "vcd_time_line.h"
#include "vcd_tokeniser.h"
#include "vector_range.h"
#include "wall_clock.h"

namespace busdecode {

namespace {

// Separators between tokens: 1 = blank (space, tab, CR, FF, VT), 3 = a newline.
constexpr auto kSeparator = [] {
    std::array<std::uint8_t, 256> k{};
    for (char c : {' ', '\t', '\r', '\f', '\v'})
        k[static_cast<unsigned char>(c)] = 1;
    k['\n'] = 3;
    return k;
}();

// The level of a state letter: IEEE 1364/1800 `0 1 x z` and VHDL's `U X 0 1 Z W L H -`
// (either case); weak levels are levels. kKeepLevel: unknown, the line keeps its level.
inline constexpr std::uint8_t kKeepLevel = 2, kNotAState = 3;
constexpr auto kStateLevel = [] {
    std::array<std::uint8_t, 256> k{};
    k.fill(kNotAState);
    for (char c : {'0', 'l', 'L'})
        k[static_cast<unsigned char>(c)] = 0;
    for (char c : {'1', 'h', 'H'})
        k[static_cast<unsigned char>(c)] = 1;
    for (char c : {'x', 'X', 'z', 'Z', 'u', 'U', 'w', 'W', '-'})
        k[static_cast<unsigned char>(c)] = kKeepLevel;
    return k;
}();

inline bool isSpace(char c) {
    return kSeparator[static_cast<unsigned char>(c)] == 1;
}

struct StringHash {
    using is_transparent = void;
    std::size_t operator()(std::string_view s) const { return std::hash<std::string_view>{}(s); }
};

// In cache lines of its own: its state is written as it reads (own_cache_lines.h).
class alignas(kOwnLineBytes) VcdReader : public VcdTokeniser {
public:
    VcdReader(std::unique_ptr<TextSource> src, const OpenOptions& opts)
        : src_(std::move(src)), name_(src_->name()), opts_(opts) {
        short1_.assign(94, -1);
        short2_.assign(94 * 94, -1);
        scalar1_.assign(256, kNotScalar);  // select() fills them
        scalar2_.assign(94 * 94, kNotScalar);
        parseHeader();
    }

    const std::vector<SignalInfo>& signals() const override { return signals_; }
    Timebase timebase() const override { return tb_; }
    std::string formatName() const override { return "vcd"; }
    std::string wallClockStart() const override { return date_; }

    void select(const std::vector<LineRef>& lines) override {
        checkSelection(lines);
        std::vector<std::vector<Target>> per_code(codes_.size());
        for (std::size_t i = 0; i < lines.size(); ++i) {
            const LineRef& r = lines[i];
            if (r.signal < 0 || r.signal >= int(signals_.size()))
                throw std::out_of_range("VcdReader::select");
            per_code[sig_code_[r.signal]].push_back({r.bit < 0 ? 0 : r.bit, std::uint32_t(i)});
        }
        targets_.clear();
        max_targets_ = 1;
        for (std::size_t c = 0; c < codes_.size(); ++c) {
            codes_[c].tbegin = std::uint32_t(targets_.size());
            targets_.insert(targets_.end(), per_code[c].begin(), per_code[c].end());
            codes_[c].tend = std::uint32_t(targets_.size());
            max_targets_ = std::max(max_targets_, per_code[c].size());
        }
        level_.assign(lines.size(), 1);
        // The one- and two-character identifiers with a single target on bit 0 (or none).
        auto scalarOf = [&](int code) {
            if (code < 0) return kNotScalar;
            const Code& c = codes_[std::size_t(code)];
            if (c.tend == c.tbegin) return kUnselected;
            if (c.tend - c.tbegin == 1 && targets_[c.tbegin].bit == 0)
                return std::int32_t(targets_[c.tbegin].line);
            return kNotScalar;
        };
        scalar1_.assign(256, kNotScalar);  // by the byte itself: no range check
        for (std::size_t i = 0; i < short1_.size(); ++i)
            scalar1_[33 + i] = scalarOf(short1_[i]);
        scalar2_.assign(94 * 94, kNotScalar);
        for (std::size_t i = 0; i < scalar2_.size(); ++i)
            scalar2_[i] = scalarOf(short2_[i]);
    }

    std::vector<std::uint8_t> initialLevels() override {
        if (!initial_done_) readInitial();
        return level_.toVector();
    }
    Tick startTick() const override { return start_; }

    bool next(EdgeBlock& block) override {
        block.clear();
        if (!initial_done_) readInitial();
        if (done_) return false;
        int idle_rounds = 0;
        for (;;) {
            Stop why = pump(&block);
            switch (why) {
                case Stop::Full:
                    block.known_until = cur_;
                    return true;
                case Stop::Eof:
                    done_ = true;
                    end_ = seen_time_ ? cur_ : start_;
                    block.known_until = end_;
                    return !block.edges.empty();
                case Stop::NoData:
                    if (!block.edges.empty() || ++idle_rounds > 20) {
                        // Live input: hand over what we have now (low latency), or an
                        // empty block now and then so the caller can stop.
                        block.known_until = cur_;
                        return true;
                    }
                    src_->waitForData(5);
                    break;
                case Stop::FirstDone:
                    break;  // not in this phase
            }
        }
    }
    Tick endTick() const override { return end_; }
    std::uint64_t bytesRead() const override { return src_->bytesRead(); }
    std::uint64_t bytesTotal() const override { return src_->bytesTotal(); }
    bool changesOnly() const override { return true; }  // see set()
    std::vector<std::string> notes() const override {
        std::vector<std::string> out;
        if (kept_only_)
            out.push_back(
                fmt::format("{} signals declared: only the {} that --map or a role names were kept",
                            declared_, signals_.size()));
        // Vivado's hardware ILA: sample indices as 1 ps times (a simulation at 1 ps steps
        // further apart); without --rate every duration is off by the sample period.
        if (vivado_ && tb_.num == 1 && tb_.den == 1'000'000'000'000 && opts_.rate_hz <= 0 &&
            first_step_ > 0 && first_step_ < 1000)
            out.push_back(
                "times look like Vivado ILA sample indices under $timescale 1ps: give the "
                "sample clock with --rate HZ for real times");
        if (unknown_states_ > 0)
            out.push_back(fmt::format(
                "{} value changes of mapped lines to x, z, u, w or -: each kept the line's "
                "level before it",
                unknown_states_));
        return out;
    }

    // ---- pieces, for SegmentedVcdReader (vcd_tokeniser.h) ----------------------

    std::unique_ptr<VcdTokeniser> clone() const override {
        return std::unique_ptr<VcdTokeniser>(new VcdReader(*this, CloneTag{}));
    }

    void tokenise(const char* b, const char* e, VcdTokenState& state,
                  std::vector<EdgeBlock>& blocks, std::size_t& used) override {
        loadState(state);
        piece_ = true;
        piece_next_ = b;
        piece_end_ = e;
        p_ = e_ = b;
        const bool seen_before = seen_time_;
        for (;;) {
            if (used == blocks.size()) blocks.emplace_back().edges.reserve(kEdgeBlockSize);
            EdgeBlock& block = blocks[used];
            block.clear();
            const Stop why = pump(&block);
            block.known_until = cur_;
            if (why != Stop::Full) {  // the end of the piece (Eof)
                if (!block.edges.empty()) ++used;
                break;
            }
            ++used;
        }
        const Tick first_time = !seen_before && seen_time_ ? start_ : state.first_time;
        state = resumeState();
        state.first_time = first_time;
    }

    std::uint64_t resumeOffset() const override {
        // p_ lies in the run of lines the source handed out last, which ends where the
        // source has read to. In the header's last line (no run yet), the line's end
        // was trimmed: not known here.
        if (!in_runs_) return kNoOffset;
        return src_->bytesRead() - std::uint64_t(e_ - p_);
    }
    VcdTokenState resumeState() const override {  // the state tokenise() leaves too
        VcdTokenState s;
        s.level = level_.toVector();
        s.cur = cur_;
        s.seen_time = seen_time_;
        s.in_block = in_block_;
        s.line = line_;
        s.unknown_states = unknown_states_;
        return s;
    }
    void resumeAt(std::uint64_t offset, const VcdTokenState& state) override {
        src_->restartAt(offset);
        loadState(state);
        piece_ = false;
        p_ = e_ = nullptr;
    }
    void finishedAt(const VcdTokenState& state) override { unknown_states_ = state.unknown_states; }
    int fileDescriptor() const override { return src_->fd(); }
    const std::string& fileName() const override { return name_; }

private:
    struct CloneTag {};
    // clone(): the header and the selection's tables, a state of its own, no source.
    VcdReader(const VcdReader& o, CloneTag)
        : name_(o.name_),
          opts_(o.opts_),
          tb_(o.tb_),
          signals_(o.signals_),
          sig_code_(o.sig_code_),
          codes_(o.codes_),
          targets_(o.targets_),
          max_targets_(o.max_targets_),
          short1_(o.short1_),
          short2_(o.short2_),
          long_(o.long_),
          unkept_ids_(o.unkept_ids_),
          unkept_code_(o.unkept_code_),
          start_(o.start_),
          time_digits_(o.time_digits_),
          last_tick_(o.last_tick_),
          fast_digits_(o.fast_digits_),
          vivado_(o.vivado_),
          first_step_(o.first_step_) {
        scalar1_.assign(o.scalar1_.size(), 0);
        std::copy_n(o.scalar1_.data(), o.scalar1_.size(), scalar1_.data());
        scalar2_.assign(o.scalar2_.size(), 0);
        std::copy_n(o.scalar2_.data(), o.scalar2_.size(), scalar2_.data());
        level_.assign(o.level_.size(), 1);
    }

    // Sets the value changes' state (tokenise(), resumeAt()): past the header and the
    // initial levels, between lines.
    void loadState(const VcdTokenState& state) {
        in_runs_ = true;
        initial_done_ = true;
        done_ = false;
        for (std::size_t i = 0; i < level_.size(); ++i)
            level_[i] = state.level[i];
        cur_ = state.cur;
        seen_time_ = state.seen_time;
        in_block_ = state.in_block;
        line_ = state.line;
        unknown_states_ = state.unknown_states;
    }

    // tokenise()'s source: the piece in runs of whole lines, as TextSource::nextLines()
    // hands out a file's (at most kMaxLine + 1 bytes, the same error past that). False at
    // the end of the piece.
    bool nextPieceLines(std::string_view& text) {
        const std::size_t left = std::size_t(piece_end_ - piece_next_);
        if (left == 0) return false;
        const std::size_t window = std::min(left, TextSource::kMaxLine + 1);
        const char* nl = static_cast<const char*>(memrchr(piece_next_, '\n', window));
        const char* end = nl ? nl + 1 : piece_end_;
        if (!nl && left > TextSource::kMaxLine)
            fail("line longer than 1 MiB (not a text capture?)");
        text = std::string_view(piece_next_, std::size_t(end - piece_next_));
        piece_next_ = end;
        return true;
    }

    struct Code {
        int width = 1;
        bool real = false;
        std::uint32_t tbegin = 0, tend = 0;  // targets_[tbegin, tend)
    };
    struct Target {
        int bit;
        std::uint32_t line;
    };
    enum class Stop { Full, Eof, NoData, FirstDone };

    // Messages name line_: the line being parsed, in the header and in the value changes.
    [[noreturn]] void fail(const std::string& what) const {
        // A capture cut short while written ends inside a line, whose rest (a time that
        // lost its last digits) is no fault of the capture as written: say so. (Runs of
        // value changes end with their newline; only the capture's last line may not.)
        const bool cut = in_runs_ && e_ && e_[-1] != '\n' && p_ <= e_ &&
                         !std::memchr(p_, '\n', std::size_t(e_ - p_));
        failAt(line_, cut ? what + "; the capture ends inside this line (cut short while written?)"
                          : what);
    }
    [[noreturn]] void failAt(std::uint64_t line, const std::string& what) const {
        throw InputError(fmt::format("{}:{}: {}", name_, line, what));
    }

    // ---- header -------------------------------------------------------------

    // Next whitespace-separated token of the header, across lines. False at the end.
    bool headerToken(std::string_view& tok) {
        for (;;) {
            while (p_ < e_ && isSpace(*p_))
                ++p_;
            if (p_ < e_) {
                const char* b = p_;
                while (p_ < e_ && !isSpace(*p_))
                    ++p_;
                tok = std::string_view(b, std::size_t(p_ - b));
                return true;
            }
            if (!nextLine()) return false;
        }
    }
    // Loads the next line into p_/e_, waiting on live input. False at the end.
    bool nextLine() {
        std::string_view line;
        for (;;) {
            auto st = src_->nextLine(line);
            if (st == TextSource::Status::Line) {
                p_ = line.data();
                e_ = line.data() + line.size();
                line_ = src_->lineNo();
                return true;
            }
            if (st == TextSource::Status::Eof) return false;
            src_->waitForData(5);
        }
    }
    // Tokens up to `$end` of the keyword `kw` (started on line `line`).
    std::vector<std::string> blockTokens(std::string_view kw, std::uint64_t line) {
        std::vector<std::string> out;
        std::string_view tok;
        for (;;) {
            if (!headerToken(tok)) failAt(line, fmt::format("{} without $end", kw));
            if (tok == "$end") return out;
            out.emplace_back(tok);
        }
    }

    void parseHeader() {
        std::string_view tok;
        std::vector<std::string> scope;
        for (;;) {
            if (!headerToken(tok)) {
                if (src_->lineNo() == 0) throw InputError(src_->name() + ": empty file");
                fail("no $enddefinitions (the header never ends)");
            }
            const std::uint64_t line = src_->lineNo();
            if (tok == "$enddefinitions") {
                blockTokens(tok, line);
                std::sort(unkept_ids_->begin(), unkept_ids_->end());
                unkept_ids_->erase(std::unique(unkept_ids_->begin(), unkept_ids_->end()),
                                   unkept_ids_->end());
                unkept_ids_->shrink_to_fit();
                if (opts_.rate_hz > 0) rateOverridesTimescale();
                limitTicks();
                break;
            } else if (tok == "$timescale") {
                parseTimescale(blockTokens(tok, line), line);
            } else if (tok == "$scope") {
                auto t = blockTokens(tok, line);
                scope.push_back(t.empty() ? std::string() : t.back());
            } else if (tok == "$upscope") {
                blockTokens(tok, line);
                if (!scope.empty()) scope.pop_back();
            } else if (tok == "$var") {
                declare(blockTokens(tok, line), scope, line);
            } else if (tok == "$date") {
                std::string text;
                for (const auto& t : blockTokens(tok, line))
                    text += (text.empty() ? "" : " ") + t;
                date_ = wallClockFromText(text);
            } else if (tok == "$version") {
                for (const auto& t : blockTokens(tok, line))
                    vivado_ |= t == "Vivado";
            } else if (tok.size() > 1 && tok[0] == '$') {
                skipBlock();  // $comment, ...
            } else {
                failAt(line, fmt::format("expected a $keyword in the VCD header, found '{}'",
                                         printable(tok)));
            }
        }
    }
    // --rate: one sample per time unit, whatever $timescale says (Vivado's hardware ILA
    // writes sample indices as 1 ps times).
    void rateOverridesTimescale() {
        const SampleRate r = sampleRateOf(opts_.rate_hz);
        if (!r.timebase) throw InputError(fmt::format("--rate {}: {}", opts_.rate_hz, r.problem));
        tb_ = *r.timebase;
    }

    // The last time this timebase allows (lastTickOf()), and the longest times fastRun()
    // may take unchecked: all of its 15 digits but where a coarse $timescale makes fewer
    // the limit.
    void limitTicks() {
        last_tick_ = lastTickOf(tb_);
        fast_digits_ = 0;
        for (Tick all_nines = 9; fast_digits_ < 15 && all_nines <= last_tick_;
             all_nines = all_nines * 10 + 9)
            ++fast_digits_;
    }

    void skipBlock() {
        std::string_view tok;
        const std::uint64_t line = src_->lineNo();
        while (headerToken(tok))
            if (tok == "$end") return;
        failAt(line, "keyword without $end");
    }

    void parseTimescale(const std::vector<std::string>& toks, std::uint64_t line) {
        std::string s;
        for (const auto& t : toks)
            s += t;
        std::size_t i = 0;
        std::int64_t n = 0;
        while (i < s.size() && s[i] >= '0' && s[i] <= '9' && n < 1000)
            n = n * 10 + (s[i++] - '0');
        const std::string unit = s.substr(i);
        static const std::pair<const char*, int> units[] = {{"s", 0},  {"ms", 3},  {"us", 6},
                                                            {"ns", 9}, {"ps", 12}, {"fs", 15}};
        int exp = -1;
        for (const auto& [u, e] : units)
            if (unit == u) exp = e;
        if ((n != 1 && n != 10 && n != 100) || exp < 0)
            failAt(line, fmt::format("expected a $timescale like 1ns, 10 us or 100 ps, found '{}'",
                                     printable(s)));
        std::int64_t den = 1;
        for (int k = 0; k < exp; ++k)
            den *= 10;
        tb_ = Timebase{n, den};
    }

    void declare(const std::vector<std::string>& t, const std::vector<std::string>& scope,
                 std::uint64_t line) {
        if (t.size() < 4) failAt(line, "expected '$var TYPE WIDTH ID NAME $end'");
        int width = 0;
        auto [ptr, ec] = std::from_chars(t[1].data(), t[1].data() + t[1].size(), width);
        if (ec != std::errc() || ptr != t[1].data() + t[1].size() || width < 1)
            failAt(line, fmt::format("expected a width in $var, found '{}'", printable(t[1])));
        const VectorName v = splitVectorName(t[3], t.size() >= 5 ? t[4] : "", width);
        const std::string& ref = v.ref;
        std::string full;
        for (const auto& s : scope)
            if (!s.empty()) full += s + ".";
        full += ref;

        const std::string& id = t[2];
        ++declared_;
        if (kept_only_ && !wanted(ref, full)) return unkept(id);
        int code = lookup(id.data(), id.size());
        if (code < 0 || code == unkept_code_) {
            code = int(codes_.size());
            Code c;
            c.width = width;
            c.real = t[0] == "real" || t[0] == "realtime";
            codes_.push_back(c);
            const auto* u = reinterpret_cast<const unsigned char*>(id.data());
            if (id.size() == 1 && unsigned(u[0] - 33) < 94) {
                short1_[u[0] - 33] = code;
            } else if (id.size() == 2 && unsigned(u[0] - 33) < 94 && unsigned(u[1] - 33) < 94) {
                short2_[(u[0] - 33) * 94 + (u[1] - 33)] = code;
            } else {
                long_.emplace(id, code);
            }
        }
        sig_code_.push_back(code);
        signals_.push_back({ref, full, width, v.msb, v.lsb});
        if (!kept_only_ && signals_.size() > kKeepAllSignals && !opts_.wanted_signals.empty())
            keepOnlyWanted();
        // A design may name a million instances' clocks "clk", but only a header made to
        // exhaust memory declares the names asked for more often (126 bytes each).
        if (kept_only_ && signals_.size() > kMaxKeptSignals)
            failAt(line, fmt::format("more than {} declarations of the signals --map and the "
                                     "roles name (of {} in all)",
                                     kMaxKeptSignals, declared_));
    }

    // ---- wide headers: memory bounded by what is mapped ----------------------------

    // Past kKeepAllSignals declarations (2^17: a simulator's 10^5 are still listed in
    // messages), the signals a decode cannot bind (no --map value,
    // role name or alias names them) are dropped; their identifiers are still known, so
    // their changes are skipped, not refused: a short one's code is unkept_code_, a long
    // one leaves only its hash in unkept_ids_ (8 bytes).
    static constexpr std::size_t kKeepAllSignals = std::size_t(1) << 17;
    static constexpr std::size_t kMaxKeptSignals = std::size_t(1) << 20;

    bool wanted(const std::string& name, const std::string& full) const {
        return wanted_.count(lowerCase(name)) != 0 || wanted_.count(lowerCase(full)) != 0;
    }
    static std::string lowerCase(std::string s) {
        for (auto& c : s)
            c = char(std::tolower(static_cast<unsigned char>(c)));
        return s;
    }
    void keepOnlyWanted() {
        kept_only_ = true;
        for (const auto& w : opts_.wanted_signals) {
            wanted_.insert(lowerCase(w));
            if (const auto lb = w.rfind('['); lb != std::string::npos && lb > 0 && w.back() == ']')
                wanted_.insert(lowerCase(w.substr(0, lb)));  // a bit of a vector
        }
        unkept_code_ = int(codes_.size());
        codes_.push_back(Code{});
        std::vector<SignalInfo> kept;
        std::vector<int> kept_code;
        for (std::size_t i = 0; i < signals_.size(); ++i)
            if (wanted(signals_[i].name, signals_[i].full_name)) {
                kept.push_back(std::move(signals_[i]));
                kept_code.push_back(sig_code_[i]);
            }
        signals_ = std::move(kept);
        sig_code_ = std::move(kept_code);
    }
    void unkept(const std::string& id) {
        const auto* u = reinterpret_cast<const unsigned char*>(id.data());
        if (id.size() == 1 && unsigned(u[0] - 33) < 94) {
            if (short1_[u[0] - 33] < 0) short1_[u[0] - 33] = unkept_code_;
        } else if (id.size() == 2 && unsigned(u[0] - 33) < 94 && unsigned(u[1] - 33) < 94) {
            int& c = short2_[(u[0] - 33) * 94 + (u[1] - 33)];
            if (c < 0) c = unkept_code_;
        } else if (long_.find(std::string_view(id)) == long_.end()) {
            unkept_ids_->push_back(idHash(id));
        }
    }
    static std::uint64_t idHash(std::string_view id) { return std::hash<std::string_view>{}(id); }

    [[gnu::always_inline]] int lookup(const char* s, std::size_t n) const {
        const auto* u = reinterpret_cast<const unsigned char*>(s);
        if (n == 1) {
            unsigned i = unsigned(u[0]) - 33;
            if (i < 94) return short1_[i];
        } else if (n == 2) {
            unsigned i = unsigned(u[0]) - 33, j = unsigned(u[1]) - 33;
            if (i < 94 && j < 94) return short2_[i * 94 + j];
        }
        if (long_.empty() && unkept_ids_->empty()) return -1;
        auto it = long_.find(std::string_view(s, n));
        if (it != long_.end()) return it->second;
        if (!unkept_ids_->empty() && std::binary_search(unkept_ids_->begin(), unkept_ids_->end(),
                                                        idHash(std::string_view(s, n))))
            return unkept_code_;
        return -1;
    }

    // ---- value changes -------------------------------------------------------

    void readInitial() {
        initial_done_ = true;
        for (;;) {
            Stop why = pump(nullptr);
            if (why == Stop::FirstDone) break;
            if (why == Stop::Eof) {
                done_ = true;
                end_ = seen_time_ ? cur_ : 0;
                break;
            }
            if (why == Stop::NoData) {
                if (seen_time_) break;  // live input: what came with the first timestamp
                src_->waitForData(5);
                if (opts_.stop && opts_.stop->load()) {
                    done_ = true;
                    break;
                }
            }
        }
        initial_ = false;
        if (seen_time_ && cur_ > start_) first_step_ = cur_ - start_;
    }

    [[gnu::always_inline]] void set(std::uint32_t line, std::uint8_t level, EdgeBlock* block) {
        if (level_[line] == level) return;
        level_[line] = level;
        if (block) block->edges.push_back({cur_, line, level});
    }

    const char* tokenEnd(const char* q) const {
        while (q<e_&& static_cast<unsigned char>(*q)> ' ')
            ++q;
        return q;
    }

    // Parses value changes. block == nullptr: the initial phase (levels only, stops at
    // the first timestamp after the start). Scans runs of whole lines (up to 1 MiB) as
    // one byte stream: a newline is a separator that counts a line, so there is no
    // per-line call or search.
    Stop pump(EdgeBlock* block) {
        for (;;) {
            while (p_ < e_) {
                const std::uint8_t k = kSeparator[static_cast<unsigned char>(*p_)];
                if (!k) break;
                line_ += k >> 1;  // a newline
                ++p_;
            }
            if (p_ >= e_) {
                if (const std::optional<Stop> why = refill()) return *why;
                continue;
            }
            if (block && seen_time_ && !in_block_) {
                fastRun(*block);
                if (p_ >= e_ || kSeparator[static_cast<unsigned char>(*p_)]) continue;
            }
            if (in_block_) {
                skipCommentToken();
                continue;
            }
            if (block && block->edges.size() + max_targets_ > kEdgeBlockSize) return Stop::Full;
            if (!takeToken(block)) return Stop::FirstDone;
        }
    }

    // The next lines into p_..e_ once these are parsed; why not, when there are none.
    std::optional<Stop> refill() {
        if (!in_runs_) {  // the header's last line is done: runs start on the next
            in_runs_ = true;
            ++line_;
        }
        std::string_view text;
        if (piece_) {
            if (!nextPieceLines(text)) return Stop::Eof;
        } else {
            auto st = src_->nextLines(text, line_);
            if (st == TextSource::Status::Eof) return Stop::Eof;
            if (st == TextSource::Status::NoData) return Stop::NoData;
        }
        p_ = text.data();
        e_ = text.data() + text.size();
        return std::nullopt;
    }

    // One token inside $comment ... $end.
    void skipCommentToken() {
        const char* q = tokenEnd(p_);
        if (q == p_) ++q;  // a control byte inside a comment
        if (std::string_view(p_, std::size_t(q - p_)) == "$end") in_block_ = false;
        p_ = q;
    }

    // The token at p_, its value changes written to `block` (null: levels only). False
    // when the initial phase is done: a time after the start, with no block.
    bool takeToken(EdgeBlock* block) {
        const char c = *p_;
        switch (c) {
            case '#':
                return takeTime(block);
            case '0':  // the bulk of these go through fastRun()
            case '1':
            case 'x':
            case 'X':
            case 'z':
            case 'Z':
            case 'u':  // VHDL's (GHDL, NVC) nine states
            case 'U':
            case 'w':
            case 'W':
            case 'l':
            case 'L':
            case 'h':
            case 'H':
            case '-':
                takeScalarChange(c, block);
                return true;
            case 'b':
            case 'B':
            case 'r':
            case 'R':
                takeVectorChange(c, block);
                return true;
            case '$':
                takeKeyword();
                return true;
            default:
                failUnexpectedToken(c);
        }
    }

    // `#time`: false when it ends the initial phase (block == nullptr).
    bool takeTime(EdgeBlock* block) {
        const DecimalScan num = scanDecimal(p_ + 1, e_);
        const char* q = num.end;
        const std::uint64_t t = num.value;
        const bool overflow = num.overflow;
        if (q == p_ + 1 || (q < e_ && !kSeparator[static_cast<unsigned char>(*q)]))
            fail(fmt::format("expected a time after '#', found '{}'",
                             printable(std::string_view(p_, std::size_t(tokenEnd(p_) - p_)))));
        // What an Edge holds (core/edge.h), which also leaves decoders room to
        // add durations to edge times: 10 hours at 1 ps. Times of up to 15
        // digits, the fast loop's, are below it.
        if (overflow || t > std::uint64_t(kMaxEdgeTick))
            fail("time beyond 2^55 - 1 ticks (36028797018963967)");
        if (t > std::uint64_t(last_tick_))
            fail(
                fmt::format("time beyond {} ticks: 146 years at this $timescale, past what "
                            "times in ns can hold",
                            last_tick_));
        p_ = q;
        const Tick tt = Tick(t);
        if (!seen_time_) {
            seen_time_ = true;
            start_ = cur_ = tt;
        } else if (tt < cur_) {
            fail(fmt::format("time going backwards (#{} after #{})", tt, cur_));
        } else if (tt > cur_) {
            cur_ = tt;
            if (!block) return false;
        }
        return true;
    }

    // A scalar value change: a level and an identifier.
    void takeScalarChange(char c, EdgeBlock* block) {
        const char* id = p_ + 1;
        const char* q = tokenEnd(id);
        if (q == id) {  // tolerate `1 !`
            while (q < e_ && isSpace(*q))
                ++q;
            id = q;
            q = tokenEnd(q);
        }
        if (!std::strchr("01xXzZ", c) && lookup(id, std::size_t(q - id)) < 0)
            fail(fmt::format(  // "hello": a stray word, not h on 'ello'
                "expected a value change, #time or $keyword, found '{}'",
                printable(std::string_view(p_, std::size_t(tokenEnd(p_) - p_)))));
        const Code& code = codeFor(id, q);
        p_ = q;
        const std::uint8_t level = kStateLevel[static_cast<unsigned char>(c)];
        if (code.tbegin != code.tend && level != kKeepLevel) {
            for (std::uint32_t k = code.tbegin; k < code.tend; ++k)
                set(targets_[k].line, targets_[k].bit == 0 ? level : 0, block);
        } else if (level == kKeepLevel) {
            unknown_states_ += code.tend - code.tbegin;
        }
    }

    // A vector (b...) or real (r...) value change, each of its bits a line.
    void takeVectorChange(char c, EdgeBlock* block) {
        const char* v = p_ + 1;
        const char* ve = tokenEnd(v);
        const char* id = ve;
        while (id < e_ && isSpace(*id))
            ++id;
        const char* q = tokenEnd(id);
        if (id == q)
            fail(fmt::format("expected an identifier after the value '{}'",
                             printable(std::string_view(p_, std::size_t(ve - p_)))));
        const Code& code = codeFor(id, q);
        p_ = q;
        if (code.tbegin == code.tend) return;
        if (c == 'r' || c == 'R') {
            double d = 0;
            auto [ptr, ec] = std::from_chars(v, ve, d);
            if (ec != std::errc() || ptr != ve)
                fail(fmt::format("expected a real number, found '{}'",
                                 printable(std::string_view(v, std::size_t(ve - v)))));
            for (std::uint32_t k = code.tbegin; k < code.tend; ++k)
                set(targets_[k].line, d != 0, block);
        } else {
            const std::size_t len = std::size_t(ve - v);
            if (len == 0) fail("expected binary digits after 'b'");
            for (std::uint32_t k = code.tbegin; k < code.tend; ++k) {
                const std::size_t bit = std::size_t(targets_[k].bit);
                // Extended the VCD way: a known leading level by 0, else itself.
                const std::uint8_t lead = kStateLevel[static_cast<unsigned char>(v[0])];
                const std::uint8_t level =
                    bit < len   ? kStateLevel[static_cast<unsigned char>(v[len - 1 - bit])]
                    : lead <= 1 ? 0
                                : kKeepLevel;
                if (level <= 1)
                    set(targets_[k].line, level, block);
                else
                    ++unknown_states_;
            }
        }
    }

    // `$keyword`: those that mark value changes are passed over, any other opens a block
    // skipped to its $end.
    void takeKeyword() {
        const char* q = tokenEnd(p_);
        std::string_view kw(p_, std::size_t(q - p_));
        p_ = q;
        if (kw == "$end" || kw == "$dumpvars" || kw == "$dumpon" || kw == "$dumpoff" ||
            kw == "$dumpall")
            return;
        in_block_ = true;  // $comment and anything else: skip to its $end
    }

    [[noreturn]] void failUnexpectedToken(char c) {
        const unsigned char u = static_cast<unsigned char>(c);
        if (u < 0x20 || u >= 0x7f)
            fail(fmt::format("binary data (byte 0x{:02x}) where a value change was expected", u));
        fail(fmt::format("expected a value change, #time or $keyword, found '{}'",
                         printable(std::string_view(p_, std::size_t(tokenEnd(p_) - p_)))));
    }

    // fastRun()'s state, handed from the loop for one length of the times to the next.
    struct FastCursor {
        const char* p;
        const char* stop;
        Edge* out;
        Edge* full;
        std::uint64_t line;
        Tick cur;
    };

    // What runTimesOf() reads its tokens with, hoisted out of `this`: a level written
    // through a byte pointer could be any member, and would make them be reloaded.
    struct FastTables {
        const std::int32_t* scalar;
        const std::int32_t* scalar2;
        std::uint8_t* level;
    };
    // What runTimesOf() does after a token: go on with the next, stop, or take the value
    // change right after a time.
    enum class FastStep { Next, Stop, ValueChange };

    // fastRun()'s loop for times of N digits. Returns the digit count of a time of
    // another length (1 to 15), for the loop of that length to take it, or 0 to stop.
    template <int N>
    int runTimesOf(FastCursor& at) {
        FastCursor c = at;  // a local: the edges written through c.out cannot alias it
        const FastTables tables{scalar1_.data(), scalar2_.data(), level_.data()};
        int next = 0;
        while (c.p < c.stop && c.out <= c.full) {
            // Each token is taken only if a separator follows it, so that pump() sees
            // any faulty token whole and words its error as it always has.
            if (*c.p == '#') {
                const FastStep step = takeFastTime<N>(c, tables, next);
                if (step == FastStep::Next) continue;
                if (step == FastStep::Stop) break;
            }
            const char ch = *c.p;
            if (unsigned(ch - '0') < 2) {
                if (!takeFastScalar(c, tables, ch)) break;
            } else if (const std::uint8_t k = kSeparator[static_cast<unsigned char>(ch)]) {
                c.line += k >> 1;  // more separators: CRLF, blank lines, a second blank
                ++c.p;
            } else {
                break;  // anything else
            }
        }
        at.p = c.p;
        at.out = c.out;
        at.line = c.line;
        at.cur = c.cur;
        return next;
    }

    // A change of a selected scalar (sel >= 0) to `value`, its time already in force.
    [[gnu::always_inline]] static void takeFastChange(FastCursor& c, const FastTables& tables,
                                                      std::int32_t sel, std::uint8_t value) {
        if (tables.level[sel] != value) {
            tables.level[sel] = value;
            *c.out++ = Edge(c.cur, std::uint32_t(sel), value);
        }
    }

    // `#time` at c.p: a whole line of one or two changes taken at once (Next), or the time
    // alone (ValueChange: a value change follows nearly every time, taken without the
    // loop's tests; nothing was written, and c.p is at most 17 bytes past c.stop, well
    // inside the 32 its 4-byte read may use). Stop, with `next` set, for a time of
    // another length; Stop for one pump() must see.
    template <int N>
    [[gnu::always_inline]] FastStep takeFastTime(FastCursor& c, const FastTables& tables,
                                                 int& next) {
        const char* const p = c.p;
        // Where the time ends is known before its digits are read: the next token's loads
        // need not wait for them.
        std::uint64_t t;
        const TimeLineShape shape = shapeOfTimeLine<N>(p + 1, t);
        // A change of a whole line: a selected or unselected scalar's value.
        const auto take = [&](std::int32_t sel, char value) {
            if (sel >= 0) takeFastChange(c, tables, sel, std::uint8_t(value - '0'));
        };
        if (shape == TimeLineShape::OneChange) {
            // `#time v!` and a newline, the whole line known good but for its identifier
            // and its time going forward; otherwise it is taken token by token below.
            const std::int32_t sel = tables.scalar[static_cast<unsigned char>(p[N + 3])];
            if (sel != kNotScalar && Tick(t) >= c.cur) [[likely]] {
                c.cur = Tick(t);
                take(sel, p[N + 2]);
                ++c.line;
                c.p = p + N + 5;
                return FastStep::Next;
            }
        } else if (shape == TimeLineShape::TwoChanges && c.out < c.full) {
            // `#time v! v"` and a newline, likewise; room for two edges (for one,
            // out <= full promises room).
            const std::int32_t s1 = tables.scalar[static_cast<unsigned char>(p[N + 3])];
            const std::int32_t s2 = tables.scalar[static_cast<unsigned char>(p[N + 6])];
            if (s1 != kNotScalar && s2 != kNotScalar && Tick(t) >= c.cur) [[likely]] {
                c.cur = Tick(t);
                take(s1, p[N + 2]);
                take(s2, p[N + 5]);
                ++c.line;
                c.p = p + N + 8;
                return FastStep::Next;
            }
        }
        const std::uint8_t k = kSeparator[static_cast<unsigned char>(p[1 + N])];
        if (shape == TimeLineShape::NotDigits || !k) [[unlikely]] {
            // A time of another length goes to its own loop. No digits, 16 or more, or no
            // separator after them: pump() reports it, or checks the range.
            const DecimalScan num = scanDecimal16(p + 1);
            if (num.digits >= 1 && num.digits <= 15 && num.digits != N) next = num.digits;
            return FastStep::Stop;
        }
        const Tick tt = Tick(t);
        if (tt < c.cur) return FastStep::Stop;  // pump() reports a time going backwards
        c.cur = tt;
        c.line += k >> 1;
        c.p = p + 2 + N;
        return FastStep::ValueChange;
    }

    // `0!` or `1!"` (an identifier of one or two bytes) at c.p, its level `ch`: false for
    // one pump() must take.
    [[gnu::always_inline]] static bool takeFastScalar(FastCursor& c, const FastTables& tables,
                                                      char ch) {
        const char* const p = c.p;
        std::uint8_t k = kSeparator[static_cast<unsigned char>(p[2])];
        std::int32_t sel;
        int len = 1;  // of the identifier
        if (k) {
            sel = tables.scalar[static_cast<unsigned char>(p[1])];
        } else {
            k = kSeparator[static_cast<unsigned char>(p[3])];
            const unsigned i = static_cast<unsigned char>(p[1]) - 33u;
            const unsigned j = static_cast<unsigned char>(p[2]) - 33u;
            if (!k || i >= 94 || j >= 94) return false;
            sel = tables.scalar2[i * 94 + j];
            len = 2;
        }
        if (sel >= 0) [[likely]] {
            takeFastChange(c, tables, sel, std::uint8_t(ch - '0'));
        } else if (sel == kNotScalar) {
            return false;
        }
        c.line += k >> 1;
        c.p = p + 2 + len;
        return true;
    }

    // runTimesOf<N> by N, 1 to 15 (0 stands for 1).
    using TimesOf = int (VcdReader::*)(FastCursor&);
    template <std::size_t... N>
    static constexpr std::array<TimesOf, 16> timesOfTable(std::index_sequence<N...>) {
        return {&VcdReader::runTimesOf<int(N == 0 ? 1 : N)>...};
    }

    // The bulk of a capture, in one tight loop: `#time` and `0!`/`1"`/`1!a` tokens of plain
    // one- and two-character scalars, separated by single blanks or newlines. It stops at anything
    // else (the general loop in pump() handles it, errors included, and calls back), at a
    // full block, and 32 bytes before the end of the run (its loads read ahead up to 17
    // bytes, and the run may end at the end of the read buffer). Behaviour is pump()'s, token
    // for token; only the dispatch and the block bookkeeping per token are gone (the
    // reading thread's instructions per line of a 10 MB SPI capture, by callgrind: 167 -> 103;
    // bench/README.md has the command). Its loop is made once per length of the times,
    // 1 to 15 digits (runTimesOf): where a time ends is then known before its digits are
    // read, and a time of another length switches loops.
    void fastRun(EdgeBlock& block) {
        if (e_ - p_ < 32 || max_targets_ >= kEdgeBlockSize) return;
        // Edges are written through a pointer into the block, sized to what the run's bytes
        // can hold (a change takes two bytes or more: a short piece fills no whole block),
        // and the block is cut back to what was written at the end.
        std::vector<Edge>& edges = block.edges;
        const std::size_t used = edges.size();
        const std::size_t room =
            std::min<std::size_t>(kEdgeBlockSize, used + max_targets_ * (std::size_t(e_ - p_) + 1));
        edges.resize(room);
        FastCursor at{p_,
                      e_ - 32,
                      edges.data() + used,
                      edges.data() + (room - max_targets_),  // pump()'s test
                      line_,
                      cur_};
        // Times grow a digit now and then (and may shrink where leading zeros were
        // written): each switch is one more call here.
        static constexpr std::array<TimesOf, 16> kTimesOf =
            timesOfTable(std::make_index_sequence<16>());
        if (time_digits_ > fast_digits_) time_digits_ = 1;
        while (const int digits = (this->*kTimesOf[time_digits_])(at)) {
            if (digits > fast_digits_) break;  // takeTime() checks it against last_tick_
            time_digits_ = digits;
        }
        edges.resize(std::size_t(at.out - edges.data()));
        p_ = at.p;
        line_ = at.line;
        cur_ = at.cur;
    }

    // Hot path: a lookup; the message is built out of line.
    [[gnu::always_inline]] const Code& codeFor(const char* id, const char* q) const {
        int code = lookup(id, std::size_t(q - id));
        if (code < 0) [[unlikely]]
            undeclared(id, q);
        return codes_[std::size_t(code)];
    }
    [[noreturn, gnu::noinline, gnu::cold]] void undeclared(const char* id, const char* q) const {
        fail(fmt::format("value change for undeclared identifier '{}'",
                         printable(std::string_view(id, std::size_t(q - id)))));
    }

    std::unique_ptr<TextSource> src_;  // null in a clone()
    std::string name_;                 // the file, for messages
    OpenOptions opts_;
    Timebase tb_{1, 1'000'000'000};
    std::vector<SignalInfo> signals_;
    std::string date_;  // $date as ISO 8601 (wall_clock.h)
    std::vector<int> sig_code_;
    std::vector<Code> codes_;
    std::vector<Target> targets_;
    std::size_t max_targets_ = 1;
    std::vector<int> short1_, short2_;
    // For fastRun(), per one-character identifier (indexed by its byte) and per
    // two-character one (like short2_: sigrok past 94 channels, many simulators): its
    // selected line, kUnselected, or kNotScalar (not declared, or several targets / a
    // vector bit: the general path in pump() handles it).
    static constexpr std::int32_t kNotScalar = -1, kUnselected = -2;
    // Read per edge on the reading thread: in lines of their own, so that no object the
    // decoding thread writes shares a line with them (own_cache_lines.h).
    OwnLinesArray<std::int32_t> scalar1_, scalar2_;
    std::unordered_map<std::string, int, StringHash, std::equal_to<>> long_;
    // keepOnlyWanted(): the long identifiers of dropped signals (hashes, sorted once the
    // header ends; shared with clones), the code that stands for them all, the names kept.
    std::shared_ptr<std::vector<std::uint64_t>> unkept_ids_ =
        std::make_shared<std::vector<std::uint64_t>>();
    int unkept_code_ = -1;
    bool kept_only_ = false;
    std::uint64_t declared_ = 0;
    std::unordered_set<std::string> wanted_;
    OwnLinesArray<std::uint8_t> level_;  // written per edge, on the reading thread

    // The rest of the current line (header), or of the current run of lines.
    const char* p_ = nullptr;
    const char* e_ = nullptr;
    std::uint64_t line_ = 0;  // number of the line p_ is in
    bool in_runs_ = false;    // p_/e_ span a run of lines from TextSource::nextLines
    bool in_block_ = false;
    bool seen_time_ = false;
    bool initial_ = true;
    bool initial_done_ = false;
    bool done_ = false;
    Tick start_ = 0, cur_ = 0, end_ = 0;
    int time_digits_ = 1;            // fastRun()'s loop: for times of this many digits
    Tick last_tick_ = kMaxEdgeTick;  // limitTicks()
    int fast_digits_ = 15;
    std::uint64_t unknown_states_ = 0;  // x z u w - on selected lines (VcdTokenState)
    bool vivado_ = false;               // $version names Vivado
    Tick first_step_ = 0;               // from the first timestamp to the second (0: none)
    // tokenise(): the piece's bytes not yet handed to pump() (piece_ set).
    bool piece_ = false;
    const char* piece_next_ = nullptr;
    const char* piece_end_ = nullptr;
};

}  // namespace

std::unique_ptr<CaptureReader> openVcd(std::unique_ptr<TextSource> src, const OpenOptions& opts) {
    // A regular file read to its end on two threads: its pieces tokenised on both
    // (segmented_vcd_reader.h), where they would otherwise take turns, one reading ahead
    // of the other decoding (prefetchReader()).
    if (opts.read_ahead && opts.read_file_ahead && src->seekable() && src->bytesTotal() > 0) {
        src->keepReadsOnThisThread();
        const std::uint64_t size = src->bytesTotal();
        return segmentedVcdReader(
            openVcdTokeniser(std::move(src), opts), size,
            opts.vcd_piece_bytes ? opts.vcd_piece_bytes : kPieceBytes,
            opts.vcd_boundary_search ? opts.vcd_boundary_search : kBoundarySearch);
    }
    return openVcdTokeniser(std::move(src), opts);
}

std::unique_ptr<VcdTokeniser> openVcdTokeniser(std::unique_ptr<TextSource> src,
                                               const OpenOptions& opts) {
    return std::make_unique<VcdReader>(std::move(src), opts);
}

}  // namespace busdecode
