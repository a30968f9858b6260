#pragma once
// State that one thread writes or reads on every edge, kept in cache lines that nothing
// else uses. The reading thread writes each line's level as it tokenises, and looks up
// each identifier; the decoding thread runs beside it on the other core. A few bytes
// from the heap share their cache line with whatever the allocator puts next to them,
// and each write by one core then takes that line away from the other (false sharing):
// a change that only moved the heap's layout (events handed on by pointer) once made
// BiSS-C's decode 12 % slower that way.
#include <algorithm>
#include <cstddef>
#include <memory>
#include <new>
#include <type_traits>
#include <vector>

namespace busdecode {

// Twice a cache line: x86 cores' adjacent-line prefetch pulls lines in pairs.
inline constexpr std::size_t kOwnLineBytes = 128;

// A fixed-size array of trivially copyable values in whole lines of its own.
template <class T>
class OwnLinesArray {
    static_assert(std::is_trivially_copyable_v<T>);

public:
    void assign(std::size_t n, T v) {
        const std::size_t bytes =
            std::max<std::size_t>(1, (n * sizeof(T) + kOwnLineBytes - 1) / kOwnLineBytes) *
            kOwnLineBytes;
        p_.reset(static_cast<T*>(::operator new(bytes, std::align_val_t(kOwnLineBytes))));
        n_ = n;
        bytes_ = bytes;
        std::fill_n(p_.get(), n, v);
    }
    std::size_t size() const { return n_; }
    // The storage it owns: whole lines, from data() on.
    std::size_t ownedBytes() const { return bytes_; }
    T* data() { return p_.get(); }
    const T* data() const { return p_.get(); }
    T& operator[](std::size_t i) { return p_[i]; }
    const T& operator[](std::size_t i) const { return p_[i]; }
    std::vector<T> toVector() const { return std::vector<T>(p_.get(), p_.get() + n_); }

private:
    struct Free {
        void operator()(T* p) const { ::operator delete(p, std::align_val_t(kOwnLineBytes)); }
    };
    std::unique_ptr<T[], Free> p_;
    std::size_t n_ = 0;
    std::size_t bytes_ = 0;
};

}  // namespace busdecode
