#include "pba/large_array.hpp"

#include <new>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace pba {

namespace {

constexpr std::size_t kLine = 64;
constexpr std::size_t kHugePage = std::size_t(2) << 20;

/// What is asked of the allocator for `bytes`: whole huge pages from one huge page up, so that
/// the advice covers this allocation alone.
std::size_t allocatedBytes(std::size_t bytes)
{
    return bytes < kHugePage ? bytes : (bytes + kHugePage - 1) / kHugePage * kHugePage;
}

std::align_val_t alignmentFor(std::size_t bytes)
{
    return std::align_val_t(bytes < kHugePage ? kLine : kHugePage);
}

} // namespace

void* allocateLargeArray(std::size_t bytes)
{
    const std::size_t size = allocatedBytes(bytes);
    void* p = ::operator new(size, alignmentFor(bytes));
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    if (size >= kHugePage)
        (void)madvise(p, size, MADV_HUGEPAGE); // advice only: refused, the pages stay small
#endif
    return p;
}

void freeLargeArray(void* p, std::size_t bytes) noexcept
{
    ::operator delete(p, alignmentFor(bytes));
}

} // namespace pba
