// vds internal: vectors for the passes over a whole mesh (validation, the
// axis count), whose arrays of tens of megabytes are fresh memory each call.
// Fresh memory costs a page fault a 4 KiB page: a million-triangle mesh's
// validation and axis count faulted about 11,600 times a call, a fifth of
// their time. In 2 MiB pages it is 512 times fewer faults for the same
// zeroing. So arrays of at least `kLargeBytes` are aligned to 2 MiB and
// offered to the kernel as huge pages (Linux's transparent huge pages,
// `madvise`; elsewhere, or where the kernel declines, plain pages).
#pragma once

#include <cstddef>
#include <cstdlib>
#include <memory>
#include <new>
#include <type_traits>
#include <utility>
#include <vector>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace vds::detail {

/// The huge page's size, and the least array that is offered them (below
/// it the padding to a whole huge page would outweigh the faults saved).
constexpr std::size_t kHugePage = std::size_t(2) << 20;
constexpr std::size_t kLargeBytes = std::size_t(4) << 20;

/// Items made without a value are default-initialised, as `new T` makes
/// them: a `LargeVector<int>(n)` or `resize(n)` leaves its new ints unset,
/// so that the threads that write them first touch (and fault) the pages in
/// parallel, not a serial zeroing pass. Give a value (`LargeVector(n, 0)`)
/// where items must start at one.
template <class T>
struct LargeAllocator {
    using value_type = T;
    LargeAllocator() = default;
    template <class U>
    LargeAllocator(const LargeAllocator<U>&) noexcept {}

    template <class U>
    void construct(U* p) noexcept(std::is_nothrow_default_constructible_v<U>) {
        ::new (static_cast<void*>(p)) U;
    }
    template <class U, class... Args>
    void construct(U* p, Args&&... args) {
        ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
    }

    T* allocate(std::size_t n) {
        if (n > std::size_t(-1) / sizeof(T) - kHugePage) throw std::bad_array_new_length();
        const std::size_t bytes = n * sizeof(T);
        if (bytes < kLargeBytes) return static_cast<T*>(::operator new(bytes));
        const std::size_t padded = (bytes + kHugePage - 1) / kHugePage * kHugePage;
        void* p = std::aligned_alloc(kHugePage, padded);
        if (!p) throw std::bad_alloc();
#if defined(__linux__) && defined(MADV_HUGEPAGE)
        (void)::madvise(p, padded, MADV_HUGEPAGE); // advice: plain pages where declined
#endif
        return static_cast<T*>(p);
    }
    void deallocate(T* p, std::size_t n) noexcept {
        if (n * sizeof(T) < kLargeBytes)
            ::operator delete(p);
        else
            std::free(p);
    }
    template <class U>
    bool operator==(const LargeAllocator<U>&) const noexcept {
        return true;
    }
    template <class U>
    bool operator!=(const LargeAllocator<U>&) const noexcept {
        return false;
    }
};

template <class T>
using LargeVector = std::vector<T, LargeAllocator<T>>;

/// An array left uninitialised (every item is written before it is read),
/// from the same allocator.
template <class T>
struct LargeDeleter {
    std::size_t n = 0;
    void operator()(T* p) const noexcept { LargeAllocator<T>().deallocate(p, n); }
};
template <class T>
using LargeArray = std::unique_ptr<T[], LargeDeleter<T>>;

template <class T>
LargeArray<T> largeArray(std::size_t n) {
    static_assert(std::is_trivially_default_constructible_v<T> && std::is_trivially_destructible_v<T>);
    return LargeArray<T>(LargeAllocator<T>().allocate(n), LargeDeleter<T>{n});
}

} // namespace vds::detail
