#pragma once
// Helpers for SpliceableDecoder::spliceState(): a decoder's fields as 64-bit words, compared for
// equality only. Doubles go in bit for bit (two states that differ in the last bit of a
// period would sample differently one day).
#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>
#include <vector>

namespace busdecode {

// The fields of a plain struct (an aggregate of scalars), counted and visited without
// naming them: a struct written whole (SpliceWords::fields()) cannot have a field left out.
namespace splice_detail {
struct AnyField {
    template <class T>
    operator T() const;
};
template <class T, class... A>
constexpr std::size_t fieldCount() {
    if constexpr (requires { T{A{}..., AnyField{}}; })
        return fieldCount<T, A..., AnyField>();
    else
        return sizeof...(A);
}
inline constexpr std::size_t kMaxFields = 20;
template <class T, class F>
constexpr void forEachField(const T& v, F&& f) {
    constexpr std::size_t n = fieldCount<T>();
    static_assert(n >= 1 && n <= kMaxFields, "forEachField: add a case for this many fields");
    auto each = [&f](const auto&... x) { (f(x), ...); };
    // clang-format off
    if constexpr (n == 1) { const auto& [a] = v; each(a); }
    else if constexpr (n == 2) { const auto& [a, b] = v; each(a, b); }
    else if constexpr (n == 3) { const auto& [a, b, c] = v; each(a, b, c); }
    else if constexpr (n == 4) { const auto& [a, b, c, d] = v; each(a, b, c, d); }
    else if constexpr (n == 5) { const auto& [a, b, c, d, e] = v; each(a, b, c, d, e); }
    else if constexpr (n == 6) { const auto& [a, b, c, d, e, g] = v; each(a, b, c, d, e, g); }
    else if constexpr (n == 7) { const auto& [a, b, c, d, e, g, h] = v; each(a, b, c, d, e, g, h); }
    else if constexpr (n == 8) { const auto& [a, b, c, d, e, g, h, i] = v; each(a, b, c, d, e, g, h, i); }
    else if constexpr (n == 9) { const auto& [a, b, c, d, e, g, h, i, j] = v; each(a, b, c, d, e, g, h, i, j); }
    else if constexpr (n == 10) { const auto& [a, b, c, d, e, g, h, i, j, k] = v; each(a, b, c, d, e, g, h, i, j, k); }
    else if constexpr (n == 11) { const auto& [a, b, c, d, e, g, h, i, j, k, l] = v; each(a, b, c, d, e, g, h, i, j, k, l); }
    else if constexpr (n == 12) { const auto& [a, b, c, d, e, g, h, i, j, k, l, m] = v; each(a, b, c, d, e, g, h, i, j, k, l, m); }
    else if constexpr (n == 13) { const auto& [a, b, c, d, e, g, h, i, j, k, l, m, o] = v; each(a, b, c, d, e, g, h, i, j, k, l, m, o); }
    else if constexpr (n == 14) { const auto& [a, b, c, d, e, g, h, i, j, k, l, m, o, p] = v; each(a, b, c, d, e, g, h, i, j, k, l, m, o, p); }
    else if constexpr (n == 15) { const auto& [a, b, c, d, e, g, h, i, j, k, l, m, o, p, q] = v; each(a, b, c, d, e, g, h, i, j, k, l, m, o, p, q); }
    else if constexpr (n == 16) { const auto& [a, b, c, d, e, g, h, i, j, k, l, m, o, p, q, r] = v; each(a, b, c, d, e, g, h, i, j, k, l, m, o, p, q, r); }
    else if constexpr (n == 17) { const auto& [a, b, c, d, e, g, h, i, j, k, l, m, o, p, q, r, s] = v; each(a, b, c, d, e, g, h, i, j, k, l, m, o, p, q, r, s); }
    else if constexpr (n == 18) { const auto& [a, b, c, d, e, g, h, i, j, k, l, m, o, p, q, r, s, t] = v; each(a, b, c, d, e, g, h, i, j, k, l, m, o, p, q, r, s, t); }
    else if constexpr (n == 19) { const auto& [a, b, c, d, e, g, h, i, j, k, l, m, o, p, q, r, s, t, u] = v; each(a, b, c, d, e, g, h, i, j, k, l, m, o, p, q, r, s, t, u); }
    else { const auto& [a, b, c, d, e, g, h, i, j, k, l, m, o, p, q, r, s, t, u, w] = v; each(a, b, c, d, e, g, h, i, j, k, l, m, o, p, q, r, s, t, u, w); }
    // clang-format on
}
// The bytes of T's fields: sizeof(T) when T has no padding.
template <class T>
constexpr std::size_t fieldBytes() {
    std::size_t n = 0;
    forEachField(T{}, [&n](const auto& x) { n += sizeof(x); });
    return n;
}
// A struct without padding: a compiler copies it whole field by field (GCC copies one with
// padding through memory, to keep the padding bytes).
template <class T>
inline constexpr bool kPaddingFree = fieldBytes<T>() == sizeof(T);
}  // namespace splice_detail

class SpliceWords {
public:
    explicit SpliceWords(std::vector<std::uint64_t>& words) : words_(words) {}

    template <class T>
    SpliceWords& operator<<(T v) {
        if constexpr (std::is_same_v<T, double>)
            words_.push_back(std::bit_cast<std::uint64_t>(v));
        else if constexpr (std::is_enum_v<T>)
            words_.push_back(std::uint64_t(v));
        else
            words_.push_back(std::uint64_t(std::int64_t(v)));
        return *this;
    }
    // Its length, then its bytes eight to a word.
    SpliceWords& operator<<(const std::string& s) {
        words_.push_back(s.size());
        for (std::size_t i = 0; i < s.size(); i += 8) {
            std::uint64_t w = 0;
            std::memcpy(&w, s.data() + i, std::min<std::size_t>(8, s.size() - i));
            words_.push_back(w);
        }
        return *this;
    }
    // Every field of a plain struct of scalars, in order: a field added to the struct is
    // compared without being listed anywhere.
    template <class T>
    SpliceWords& fields(const T& v) {
        static_assert(std::is_aggregate_v<T> && std::is_trivially_copyable_v<T>);
        splice_detail::forEachField(v, [this](const auto& x) { *this << x; });
        return *this;
    }

private:
    std::vector<std::uint64_t>& words_;
};

}  // namespace busdecode
