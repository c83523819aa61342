#pragma once
// Memory for the large arrays that a swarm streams through every step (and that `pba bench`'s
// bandwidth bound streams through for comparison).
#include <cstddef>
#include <vector>

namespace pba {

/// `bytes` of memory aligned to a cache line; from 2 MiB up, aligned to 2 MiB, rounded up to
/// whole 2 MiB, and (on Linux) advised to the kernel as transparent huge pages before anything
/// touches it. A step streams six arrays of 4 KB pages through the TLB, which maps 12 MB of
/// them: every page of a larger swarm is a page walk, and the hardware prefetchers stop at
/// page boundaries (docs/performance.md has what it saves at 1e7). NumPy advises its large
/// arrays the same way.
/// Where the kernel has no huge pages to give (or is not Linux) the memory is ordinary.
void* allocateLargeArray(std::size_t bytes);
/// Frees what allocateLargeArray(bytes) returned, with the same `bytes`.
void freeLargeArray(void* p, std::size_t bytes) noexcept;

/// allocateLargeArray as a standard allocator (for std::vector).
template <class T>
struct LargeArrayAllocator {
    using value_type = T;
    LargeArrayAllocator() = default;
    template <class U>
    LargeArrayAllocator(const LargeArrayAllocator<U>&) noexcept
    {
    }
    T* allocate(std::size_t n) { return static_cast<T*>(allocateLargeArray(n * sizeof(T))); }
    void deallocate(T* p, std::size_t n) noexcept { freeLargeArray(p, n * sizeof(T)); }
    template <class U>
    bool operator==(const LargeArrayAllocator<U>&) const noexcept
    {
        return true;
    }
};

/// A std::vector in such memory: a swarm's state, the bound's array.
template <class T>
using LargeArray = std::vector<T, LargeArrayAllocator<T>>;

} // namespace pba
