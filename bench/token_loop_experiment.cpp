// Shapes of the VCD token loop, timed on one capture held in memory (no kernel
// copy, no decoder): which one a faster tokeniser should take. An experiment, not part
// of `decode`: the loops keep only what VcdReader::fastRun() does per token on
// make_capture's files (one-character identifiers, `#time` starting every line).
//
//     token_loop_experiment FILE [RUNS]
//
// - single:      fastRun()'s shape: one token after the other, each token's end found
//                by parsing it (the next token's start depends on this one's digits).
// - two-streams: each 64 KiB chunk split at a line starting with '#' near its middle, the
//                two halves parsed in one loop, a token of each in turn: two independent
//                chains, so a loop bound by the latency from one token's end to the
//                next token's start would run up to twice as fast.
// - whole-lines: stop 40's first step: a whole `#time v!` line after one test of its
//                shape (capture/vcd_time_line.h), anything else token by token.
// - both-shapes: whole-lines with the two-change line (`#time v! v"`) taken whole too,
//                each shape on its own branch: runTimesOf()'s shape since stop 40.
// - line-index:  (stop 41) the lines of each 64 KiB chunk found first, 64 bytes at a
//                time (their starts written eight at a time, no branch per line), then
//                each taken whole with its start from that index, one change or two
//                without a branch on which. TOKEN_LOOP_STAGE1_ONLY=1 times the first
//                stage alone.
// - masks:       (x86-64 with AVX2) separators found 64 bytes at a time; each token's
//                start and length come from the masks, and its time or edge is taken
//                without a branch on its kind or its data.
// Each prints the median of RUNS (default 5) passes, and the edges and lines it counted
// (all must agree with read_capture's edges).
#include <algorithm>
#include <array>
#include <bit>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>
#include <utility>
#include <vector>

#if defined(__x86_64__)
#include <immintrin.h>
#endif

#include "capture/decimal_scan.h"
#include "capture/vcd_time_line.h"

namespace {

using busdecode::DecimalScan;
using busdecode::scanDecimal16;

struct Edge {
    Edge() noexcept {}  // NOLINT: left uninitialised, as busdecode::Edge
    Edge(std::uint64_t t_, std::uint32_t line_, std::uint8_t level_) noexcept
        : t(t_), line(line_), level(level_) {}
    std::uint64_t t;
    std::uint32_t line;
    std::uint8_t level;
};

constexpr std::size_t kChunk = 64 << 10;
constexpr unsigned kNoLine = 63;  // the level slot a time token writes to (never read)

// Per one-character identifier (id - 33): its line, or -1 (not declared).
std::array<std::int32_t, 94> g_line;

struct Cursor {
    const char* p;
    std::uint64_t cur = 0;
    std::uint64_t lines = 0;
    Edge* out;
    std::uint8_t* level;
};

[[noreturn]] void unsupported(const char* where) {
    std::fprintf(stderr, "token_loop_experiment: %s: not a make_capture VCD\n", where);
    std::exit(2);
}

// One token and the separator after it, as fastRun() takes it.
[[gnu::always_inline]] inline void step(Cursor& s) {
    const char* p = s.p;
    char c = *p;
    if (c == '#') {
        const DecimalScan num = scanDecimal16(p + 1);
        if (num.digits == 0 || num.digits >= 16 || num.value < s.cur) unsupported("time");
        s.cur = num.value;
        s.lines += *num.end == '\n';
        p = num.end + 1;
        c = *p;
    }
    if (unsigned(c - '0') < 2) {
        const unsigned i = static_cast<unsigned char>(p[1]) - 33u;
        if (i >= 94 || g_line[i] < 0 || static_cast<unsigned char>(p[2]) > ' ')
            unsupported("value change");
        const auto sel = unsigned(g_line[i]);
        const auto v = std::uint8_t(c - '0');
        if (s.level[sel] != v) {
            s.level[sel] = v;
            *s.out++ = Edge(s.cur, sel, v);
        }
        s.lines += p[2] == '\n';
        p += 3;
    } else if (static_cast<unsigned char>(c) <= ' ') {
        s.lines += c == '\n';
        ++p;
    } else {
        unsupported("token");
    }
    s.p = p;
}

struct Totals {
    std::uint64_t edges = 0, lines = 0;
};

Totals runSingle(const char* p, const char* stop, Edge* buf, std::uint8_t* level) {
    Totals n;
    Cursor s{p, 0, 0, buf, level};
    while (s.p < stop) {
        const char* ce = std::min(stop, s.p + kChunk);
        s.out = buf;
        while (s.p < ce)
            step(s);
        n.edges += std::uint64_t(s.out - buf);
    }
    n.lines = s.lines;
    return n;
}

// The line of a one-character identifier, or -1 (out of range, or not declared).
inline std::int32_t lineOfId(char id) {
    const unsigned i = static_cast<unsigned char>(id) - 33u;
    return i < 94 ? g_line[i] : -1;
}

// A change of line `sel` (declared) to `value` ('0' or '1') at time t: an edge if its
// level moves.
inline void takeChange(Cursor& s, std::uint64_t t, std::int32_t sel, char value) {
    const auto v = std::uint8_t(value - '0');
    if (s.level[sel] != v) {
        s.level[sel] = v;
        *s.out++ = Edge(t, unsigned(sel), v);
    }
}

// Stop 40's first step: a whole `#time v!` line after one test of its shape
// (capture/vcd_time_line.h), any other token by step(); with none of fastRun()'s block,
// piece or error bookkeeping (bench/README.md, "Whole time lines in one test"). False at
// a line it does not take.
template <int N>
bool wholeLinesOf(Cursor& s, const char* ce) {
    while (s.p < ce) {
        const char* p = s.p;
        std::uint64_t t;
        if (*p != '#' ||
            busdecode::shapeOfTimeLine<N>(p + 1, t) != busdecode::TimeLineShape::OneChange)
            return false;
        const std::int32_t sel = lineOfId(p[N + 3]);
        if (sel < 0 || t < s.cur) return false;
        s.cur = t;
        takeChange(s, t, sel, p[N + 2]);
        ++s.lines;
        s.p = p + N + 5;
    }
    return true;
}

template <std::size_t... N>
constexpr std::array<bool (*)(Cursor&, const char*), sizeof...(N)> wholeLinesTable(
    std::index_sequence<N...>) {
    return {&wholeLinesOf<int(N == 0 ? 1 : N)>...};
}

// Each line of a `#time` of 1 to kMaxDigits digits through that length's loop in `of`
// (until a line it does not take), any other token by step().
template <std::size_t kMaxDigits>
Totals runLineLoops(const std::array<bool (*)(Cursor&, const char*), kMaxDigits + 1>& of,
                    const char* p, const char* stop, Edge* buf, std::uint8_t* level) {
    Totals n;
    Cursor s{p, 0, 0, buf, level};
    while (s.p < stop) {
        const char* ce = std::min(stop, s.p + kChunk);
        s.out = buf;
        while (s.p < ce) {
            if (*s.p == '#') {
                const int d = scanDecimal16(s.p + 1).digits;
                if (d >= 1 && std::size_t(d) <= kMaxDigits && of[std::size_t(d)](s, ce)) continue;
            }
            step(s);
        }
        n.edges += std::uint64_t(s.out - buf);
    }
    n.lines = s.lines;
    return n;
}

Totals runWholeLines(const char* p, const char* stop, Edge* buf, std::uint8_t* level) {
    static constexpr auto kOf =
        wholeLinesTable(std::make_index_sequence<busdecode::kOneChangeMaxDigits + 1>());
    return runLineLoops<busdecode::kOneChangeMaxDigits>(kOf, p, stop, buf, level);
}

// Both line shapes whole, `#time v!` and `#time v! v"`, each on its own branch, as
// VcdReader::runTimesOf() takes them since stop 40. False at a line it does not take.
template <int N>
bool bothShapesOf(Cursor& s, const char* ce) {
    while (s.p < ce) {
        const char* p = s.p;
        std::uint64_t t;
        if (*p != '#') return false;
        const busdecode::TimeLineShape shape = busdecode::shapeOfTimeLine<N>(p + 1, t);
        if (t < s.cur) return false;
        const std::int32_t sel1 = lineOfId(p[N + 3]);
        if (shape == busdecode::TimeLineShape::OneChange) {
            if (sel1 < 0) return false;
            s.cur = t;
            takeChange(s, t, sel1, p[N + 2]);
            s.p = p + N + 5;
        } else if (shape == busdecode::TimeLineShape::TwoChanges) {
            const std::int32_t sel2 = lineOfId(p[N + 6]);
            if (sel1 < 0 || sel2 < 0) return false;
            s.cur = t;
            takeChange(s, t, sel1, p[N + 2]);
            takeChange(s, t, sel2, p[N + 5]);
            s.p = p + N + 8;
        } else {
            return false;
        }
        ++s.lines;
    }
    return true;
}

// Newlines of 64 bytes, a bit each (SSE2; a byte loop elsewhere).
inline std::uint64_t newlines64(const char* p) {
    std::uint64_t m = 0;
#if defined(__SSE2__)
    const __m128i nl = _mm_set1_epi8('\n');
    for (int k = 0; k < 4; ++k) {
        const __m128i x = _mm_loadu_si128(reinterpret_cast<const __m128i*>(p + 16 * k));
        m |= std::uint64_t(unsigned(_mm_movemask_epi8(_mm_cmpeq_epi8(x, nl)))) << (16 * k);
    }
#else
    for (int k = 0; k < 64; ++k)
        m |= std::uint64_t(p[k] == '\n') << k;
#endif
    return m;
}

// The lines of [p, ce) found first (their starts into `at`, eight at a time without a
// branch per line), then each taken whole, one-change or two-change, without a branch on
// which: a line's start does not depend on the line before it. Returns the lines taken
// (all of them, or up to the first it cannot take).
template <int N>
std::size_t indexedLinesOf(Cursor& s, const char* base, const std::uint32_t* at, std::size_t from,
                           std::size_t count) {
    // The cursor's fields in locals: an edge's store may alias them (as seen by the
    // compiler), and a count kept in memory would chain every line to the one before.
    Edge* out = s.out;
    std::uint8_t* const level = s.level;
    std::uint64_t cur = s.cur;
    std::size_t i = from;
    for (; i < count; ++i) {
        const char* p = base + at[i];
        const std::size_t len = at[i + 1] - at[i];  // with its newline
        std::uint64_t t;
        const busdecode::TimeLineShape shape = busdecode::shapeOfTimeLine<N>(p + 1, t);
        const bool one = len == std::size_t(N + 5);
        const bool two = len == std::size_t(N + 8);
        const std::int32_t line1 = lineOfId(p[N + 3]);
        const std::int32_t line2 = two ? lineOfId(p[N + 6]) : line1;
        const bool shape_ok = (one & (shape == busdecode::TimeLineShape::OneChange)) |
                              (two & (shape == busdecode::TimeLineShape::TwoChanges));
        if (*p != '#' || !shape_ok || t < cur || line1 < 0 || line2 < 0) break;
        const auto sel1 = unsigned(line1), sel2 = unsigned(line2);
        const auto v1 = std::uint8_t(p[N + 2] & 1), v2 = std::uint8_t(p[N + 5] & 1);
        // Every change a real one (a predictable branch: a VCD writes changes): both
        // edges written, the second counted for a two-change line.
        if (level[sel1] == v1 || (two && (level[sel2] == v2 || sel2 == sel1))) break;
        cur = t;
        level[sel1] = v1;
        level[sel2] = two ? v2 : v1;
        out[0] = Edge(t, sel1, v1);
        out[1] = Edge(t, sel2, v2);
        out += 1 + int(two);
    }
    s.out = out;
    s.cur = cur;
    s.lines += i - from;
    return i;
}

template <std::size_t... N>
constexpr std::array<bool (*)(Cursor&, const char*), sizeof...(N)> bothShapesTable(
    std::index_sequence<N...>) {
    return {&bothShapesOf<int(N == 0 ? 1 : N)>...};
}
template <std::size_t... N>
constexpr std::array<std::size_t (*)(Cursor&, const char*, const std::uint32_t*, std::size_t,
                                     std::size_t),
                     sizeof...(N)>
indexedTable(std::index_sequence<N...>) {
    return {&indexedLinesOf<int(N == 0 ? 1 : N)>...};
}

Totals runBothShapes(const char* p, const char* stop, Edge* buf, std::uint8_t* level) {
    static constexpr auto kOf =
        bothShapesTable(std::make_index_sequence<busdecode::kTwoChangesMaxDigits + 1>());
    return runLineLoops<busdecode::kTwoChangesMaxDigits>(kOf, p, stop, buf, level);
}

Totals runIndexed(const char* p, const char* stop, Edge* buf, std::uint8_t* level) {
    static constexpr auto kOf =
        indexedTable(std::make_index_sequence<busdecode::kTwoChangesMaxDigits + 1>());
    static std::vector<std::uint32_t> at(kChunk + 64);
    Totals n;
    Cursor s{p, 0, 0, buf, level};
    while (s.p < stop) {
        const char* base = s.p;
        const char* ce = std::min(stop, base + kChunk);
        // Stage 1: where each line starts (after each newline), the first at 0.
        std::size_t count = 0;
        at[count++] = 0;
        for (const char* q = base; q < ce; q += 64) {
            std::uint64_t m = newlines64(q);
            if (ce - q < 64) m &= (std::uint64_t(1) << (ce - q)) - 1;
            const auto off = std::uint32_t(q - base) + 1;
            const int c = __builtin_popcountll(m);
            std::uint32_t* w = &at[count];
            for (int j = 0; j < 8; ++j) {
                w[j] = off + std::uint32_t(std::countr_zero(m));
                m &= m - 1;
            }
            for (int j = 8; j < c; ++j) {
                w[j] = off + std::uint32_t(std::countr_zero(m));
                m &= m - 1;
            }
            count += std::size_t(c);
        }
        // Lines 0 .. count-2 are whole ([at[i], at[i+1])); the rest goes to the next chunk.
        const std::size_t whole = count - 1;
        if (whole == 0) unsupported("a line longer than a chunk");
        s.out = buf;
        std::size_t i = 0;
        // TOKEN_LOOP_STAGE1_ONLY=1: the lines found and nothing taken, to time the first
        // stage alone (bench/README.md, stop 41).
        static const bool stage1_only = std::getenv("TOKEN_LOOP_STAGE1_ONLY") != nullptr;
        if (stage1_only) i = whole;
        while (i < whole) {
            const char* l = base + at[i];
            if (*l == '#') {
                const int d = scanDecimal16(l + 1).digits;
                if (d >= 1 && d <= busdecode::kTwoChangesMaxDigits) {
                    const std::size_t j = kOf[std::size_t(d)](s, base, at.data(), i, whole);
                    if (j != i) {
                        i = j;
                        continue;
                    }
                }
            }
            // Any other line, token by token.
            s.p = l;
            const char* e = base + at[i + 1];
            while (s.p < e)
                step(s);
            ++i;
        }
        s.p = base + at[whole];
        n.edges += std::uint64_t(s.out - buf);
    }
    n.lines = s.lines;
    return n;
}

Totals runTwoStreams(const char* p, const char* stop, Edge* buf, Edge* buf2, std::uint8_t* level) {
    Totals n;
    std::uint8_t level2[64];
    std::uint64_t cur = 0;
    while (p < stop) {
        const char* ce = std::min(stop, p + kChunk);
        const char* mid = p + (ce - p) / 2;
        const char* m = static_cast<const char*>(std::memchr(mid, '\n', std::size_t(ce - mid)));
        if (!m || m + 1 >= ce || m[1] != '#') unsupported("chunk split");
        ++m;
        // The second half starts with unknown levels: every value change is an edge there
        // (the reader would drop the repeats when appending it).
        std::memset(level2, 2, sizeof level2);
        Cursor a{p, cur, 0, buf, level}, b{m, 0, 0, buf2, level2};
        while (a.p < m && b.p < ce) {
            step(a);
            step(b);
        }
        while (a.p < m)
            step(a);
        while (b.p < ce)
            step(b);
        // Merging the halves: a line's first change in the second half is no edge if it
        // repeats the level the first half ended with.
        std::uint64_t repeats = 0;
        bool seen[64] = {};
        for (const Edge* e = buf2; e != b.out; ++e) {
            if (seen[e->line]) continue;
            seen[e->line] = true;
            repeats += e->level == level[e->line];
        }
        for (unsigned k = 0; k < 64; ++k)
            if (level2[k] != 2) level[k] = level2[k];
        n.edges += std::uint64_t(a.out - buf) + std::uint64_t(b.out - buf2) - repeats;
        n.lines += a.lines + b.lines;
        cur = b.cur;
        p = b.p;
    }
    return n;
}

#if defined(__x86_64__)
// Separators (bytes up to ' '; none from 0x80 up) and newlines of 32 bytes, a bit each.
__attribute__((target("avx2"))) inline std::uint32_t separators32(__m256i v) {
    const __m256i below = _mm256_set1_epi8(0x21);
    return std::uint32_t(_mm256_movemask_epi8(_mm256_cmpgt_epi8(below, v))) &
           ~std::uint32_t(_mm256_movemask_epi8(v));
}
__attribute__((target("avx2"))) inline std::uint32_t newlines32(__m256i v) {
    return std::uint32_t(_mm256_movemask_epi8(_mm256_cmpeq_epi8(v, _mm256_set1_epi8('\n'))));
}

__attribute__((target("avx2,bmi,popcnt"))) Totals runMasks(const char* p, const char* stop,
                                                           Edge* buf, std::uint8_t* level) {
    Totals n;
    std::uint64_t cur = 0;
    // Whether the byte before the block is a separator: a token starts after one.
    std::uint64_t prev_sep = 1;
    Edge* out = buf;
    for (; p + 64 <= stop; p += 64) {
        if (out - buf > std::ptrdiff_t(kChunk)) {
            n.edges += std::uint64_t(out - buf);
            out = buf;
        }
        const __m256i x = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(p));
        const __m256i y = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(p + 32));
        const std::uint64_t sep = separators32(x) | (std::uint64_t(separators32(y)) << 32);
        n.lines += std::uint64_t(
            __builtin_popcountll(newlines32(x) | (std::uint64_t(newlines32(y)) << 32)));
        std::uint64_t starts = ~sep & ((sep << 1) | prev_sep);
        prev_sep = sep >> 63;
        while (starts) {
            const unsigned i = unsigned(__builtin_ctzll(starts));
            starts &= starts - 1;
            const char* q = p + i;
            const std::uint64_t after = sep >> i;
            unsigned len = after ? unsigned(__builtin_ctzll(after)) : 64;
            if (!after)  // the token runs into the next block
                for (len = 0; static_cast<unsigned char>(q[len]) > ' ';)
                    ++len;
            const bool is_time = q[0] == '#';
            const DecimalScan d = scanDecimal16(q + 1);
            const unsigned id = static_cast<unsigned char>(q[1]) - 33u;
            const bool time_ok =
                d.digits > 0 && d.digits < 16 && unsigned(d.digits) + 1 == len && d.value >= cur;
            const bool value_ok = unsigned(q[0] - '0') < 2 && len == 2 && id < 94;
            const std::int32_t sel = g_line[value_ok ? id : 0];
            if (is_time ? !time_ok : (!value_ok || sel < 0)) unsupported("token");
            cur = is_time ? d.value : cur;
            const auto v = std::uint8_t(q[0] - '0');
            const unsigned slot = is_time ? kNoLine : unsigned(sel);
            const bool edge = slot != kNoLine && level[slot] != v;
            level[slot] = v;
            *out = Edge(cur, unsigned(sel), v);
            out += edge;
        }
    }
    n.edges += std::uint64_t(out - buf);
    return n;
}
#endif

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2 || argc > 3) {
        std::fprintf(stderr, "usage: token_loop_experiment FILE [RUNS]\n");
        return 2;
    }
    const int runs = argc == 3 ? std::max(1, std::atoi(argv[2])) : 5;
    std::ifstream in(argv[1], std::ios::binary);
    if (!in) unsupported(argv[1]);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    // The header's `$var wire 1 ID NAME $end` lines, in order: line k is the k-th.
    g_line.fill(-1);
    const std::size_t hdr_end = text.find("$enddefinitions");
    if (hdr_end == std::string::npos) unsupported("header");
    int lines_declared = 0;
    for (std::size_t v = text.find("$var"); v < hdr_end; v = text.find("$var", v + 4)) {
        char type[32], id[32];
        int width = 0;
        if (std::sscanf(text.c_str() + v, "$var %31s %d %31s", type, &width, id) != 3 ||
            width != 1 || std::strlen(id) != 1 || lines_declared >= 4)
            unsupported("$var");
        g_line[static_cast<unsigned char>(id[0]) - 33] = lines_declared++;
    }
    const std::size_t first = text.find("\n#", hdr_end);
    if (first == std::string::npos) unsupported("value changes");
    // Whole lines only, and 64 readable bytes past the last one for the loops' loads.
    const std::size_t last_nl =
        text.rfind('\n', text.size() - 1 - std::min<std::size_t>(text.size() - 1, 64));
    const char* begin = text.data() + first + 1;
    const char* stop = text.data() + last_nl + 1;
    std::vector<Edge> buf(kChunk + 64), buf2(kChunk + 64);

    struct Mode {
        const char* name;
        Totals (*run)(const char*, const char*, Edge*, Edge*, std::uint8_t*);
    };
    std::vector<Mode> modes = {
        {"single", [](const char* b, const char* s, Edge* e, Edge*,
                      std::uint8_t* l) { return runSingle(b, s, e, l); }},
        {"two-streams", runTwoStreams},
        {"whole-lines", [](const char* b, const char* s, Edge* e, Edge*,
                           std::uint8_t* l) { return runWholeLines(b, s, e, l); }},
        {"both-shapes", [](const char* b, const char* s, Edge* e, Edge*,
                           std::uint8_t* l) { return runBothShapes(b, s, e, l); }},
        {"line-index", [](const char* b, const char* s, Edge* e, Edge*,
                          std::uint8_t* l) { return runIndexed(b, s, e, l); }},
    };
#if defined(__x86_64__)
    if (__builtin_cpu_supports("avx2"))
        modes.push_back(
            {"masks", [](const char* b, const char* s, Edge* e, Edge*, std::uint8_t* l) {
                 // Blocks of 64 bytes from the first line: end on a whole block.
                 return runMasks(b, b + (s - b) / 64 * 64, e, l);
             }});
#endif
    for (const Mode& m : modes) {
        std::vector<double> ms;
        Totals n;
        for (int r = 0; r < runs; ++r) {
            std::uint8_t level[64];
            std::memset(level, 1, sizeof level);
            const auto t0 = std::chrono::steady_clock::now();
            n = m.run(begin, stop, buf.data(), buf2.data(), level);
            const auto t1 = std::chrono::steady_clock::now();
            ms.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
        }
        std::sort(ms.begin(), ms.end());
        std::printf("%-12s %8.1f ms (median of %d; %.1f-%.1f)  %llu edges, %llu lines\n", m.name,
                    ms[ms.size() / 2], runs, ms.front(), ms.back(),
                    static_cast<unsigned long long>(n.edges),
                    static_cast<unsigned long long>(n.lines));
    }
    return 0;
}
