#pragma once
// A column's values while read() builds it: a growing array of plain numbers in memory
// of its own (mmap), which grows by mremap, without copying what it holds, and in huge
// pages once it is large, so that columns of a million rows or more take a page fault
// per 2 MB and not per 4 KB. Handed to numpy as is (read_py.cpp).
#include <cstddef>
#include <new>
#include <type_traits>
#include <utility>

#include <sys/mman.h>

namespace busdecode::py {

template <class T>
class LaneBuffer {
    static_assert(std::is_trivially_copyable_v<T>);

public:
    LaneBuffer() = default;
    LaneBuffer(const LaneBuffer&) = delete;
    LaneBuffer& operator=(const LaneBuffer&) = delete;
    LaneBuffer(LaneBuffer&& o) noexcept { swap(o); }
    LaneBuffer& operator=(LaneBuffer&& o) noexcept {
        LaneBuffer gone(std::move(*this));
        swap(o);
        return *this;
    }
    ~LaneBuffer() {
        if (data_) ::munmap(data_, bytes_);
    }

    void push_back(T v) {
        if (size_ == bytes_ / sizeof(T)) grow();
        data_[size_++] = v;
    }
    void pop_back() { --size_; }
    std::size_t size() const { return size_; }
    bool empty() const { return size_ == 0; }
    T* data() { return data_; }
    const T* data() const { return data_; }
    T& operator[](std::size_t i) { return data_[i]; }
    const T& operator[](std::size_t i) const { return data_[i]; }
    const T& back() const { return data_[size_ - 1]; }
    const T* begin() const { return data_; }
    const T* end() const { return data_ + size_; }

private:
    // Small columns (a capture's few register accesses) take 64 KB of address space and
    // a page or two; only a column past kHugeFrom is worth 2 MB pages. From 2 MB, the
    // 3 MB columns of a 375 000-row capture were no faster and took 21 MB more at peak.
    static constexpr std::size_t kFirstBytes = std::size_t(64) << 10;
    static constexpr std::size_t kHugeFrom = std::size_t(8) << 20;

    [[gnu::noinline]] void grow() {  // rare: push_back stays small enough to inline
        const std::size_t bytes = bytes_ ? bytes_ * 2 : kFirstBytes;
        void* p = data_ ? ::mremap(data_, bytes_, bytes, MREMAP_MAYMOVE)
                        : ::mmap(nullptr, bytes, PROT_READ | PROT_WRITE,
                                 MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
        if (p == MAP_FAILED) throw std::bad_alloc();
        if (bytes >= kHugeFrom) ::madvise(p, bytes, MADV_HUGEPAGE);  // a hint: may be ignored
        data_ = static_cast<T*>(p);
        bytes_ = bytes;
    }
    void swap(LaneBuffer& o) noexcept {
        std::swap(data_, o.data_);
        std::swap(size_, o.size_);
        std::swap(bytes_, o.bytes_);
    }

    T* data_ = nullptr;
    std::size_t size_ = 0;
    std::size_t bytes_ = 0;  // mapped
};

}  // namespace busdecode::py
