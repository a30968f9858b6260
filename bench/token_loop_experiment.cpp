// Three shapes of the VCD token loop, timed on one capture held in memory (no kernel
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
// - whole-lines: fastRun()'s shape since stop 40: a whole `#time v!` line after one test
//                of its shape (capture/vcd_time_line.h), anything else token by token.
// - masks:       (x86-64 with AVX2) separators found 64 bytes at a time; each token's
//                start and length come from the masks, and its time or edge is taken
//                without a branch on its kind or its data.
// Each prints the median of RUNS (default 5) passes, and the edges and lines it counted
// (all three must agree with read_capture's edges).
#include <algorithm>
#include <array>
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

// fastRun()'s shape since stop 40: a whole `#time v!` line after one test of its shape
// (capture/vcd_time_line.h), any other token by step(); with none of fastRun()'s block,
// piece or error bookkeeping, the floor of the tokeniser as it is now (bench/README.md,
// "Whole time lines in one test"). False at a line it does not take.
template <int N>
bool wholeLinesOf(Cursor& s, const char* ce) {
    while (s.p < ce) {
        const char* p = s.p;
        std::uint64_t t;
        if (*p != '#' ||
            busdecode::shapeOfTimeLine<N>(p + 1, t) != busdecode::TimeLineShape::OneChange)
            return false;
        const unsigned i = static_cast<unsigned char>(p[N + 3]) - 33u;
        if (i >= 94 || g_line[i] < 0 || t < s.cur) return false;
        s.cur = t;
        const auto sel = unsigned(g_line[i]);
        const auto v = std::uint8_t(p[N + 2] - '0');
        if (s.level[sel] != v) {
            s.level[sel] = v;
            *s.out++ = Edge(t, sel, v);
        }
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

Totals runWholeLines(const char* p, const char* stop, Edge* buf, std::uint8_t* level) {
    static constexpr auto kOf =
        wholeLinesTable(std::make_index_sequence<busdecode::kOneChangeMaxDigits + 1>());
    Totals n;
    Cursor s{p, 0, 0, buf, level};
    while (s.p < stop) {
        const char* ce = std::min(stop, s.p + kChunk);
        s.out = buf;
        while (s.p < ce) {
            if (*s.p == '#') {
                const int d = scanDecimal16(s.p + 1).digits;
                if (d >= 1 && d <= busdecode::kOneChangeMaxDigits && kOf[std::size_t(d)](s, ce))
                    continue;
            }
            step(s);
        }
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
