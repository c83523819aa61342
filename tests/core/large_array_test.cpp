// The memory a swarm's state lives in: aligned to a cache line, and from 2 MiB up to a huge page
// and advised to the kernel as one (Linux), whatever the kernel then makes of the advice.
#include <gtest/gtest.h>

#include <cstdint>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "pba/large_array.hpp"

using namespace pba;

namespace {

std::uintptr_t address(const void* p)
{
    return reinterpret_cast<std::uintptr_t>(p);
}

#if defined(__linux__)
/// The VmFlags line of the mapping in /proc/self/smaps that holds p ("" if none is found).
std::string mappingFlags(const void* p)
{
    std::ifstream smaps("/proc/self/smaps");
    std::string line;
    bool inside = false;
    while (std::getline(smaps, line)) {
        std::uintptr_t from = 0, to = 0;
        char dash = 0;
        std::istringstream range(line);
        if (range >> std::hex >> from >> dash >> to && dash == '-' && line.find(':') > line.find(' ')) {
            inside = from <= address(p) && address(p) < to;
            continue;
        }
        if (inside && line.rfind("VmFlags:", 0) == 0)
            return line;
    }
    return "";
}
#endif

} // namespace

TEST(LargeArray, SmallArraysAreAlignedToACacheLine)
{
    for (std::size_t bytes : {std::size_t(4), std::size_t(1000), std::size_t(1) << 20}) {
        void* p = allocateLargeArray(bytes);
        EXPECT_EQ(address(p) % 64, 0u) << bytes;
        freeLargeArray(p, bytes);
    }
}

TEST(LargeArray, LargeArraysAreAlignedToAHugePageAndWritableToTheirEnd)
{
    const std::size_t bytes = (std::size_t(5) << 20) + 12; // not a whole number of huge pages
    auto* p = static_cast<unsigned char*>(allocateLargeArray(bytes));
    EXPECT_EQ(address(p) % (std::size_t(2) << 20), 0u);
    for (std::size_t i = 0; i < bytes; i += 4096)
        p[i] = 1;
    p[bytes - 1] = 2;
    EXPECT_EQ(p[bytes - 1], 2);
    freeLargeArray(p, bytes);
}

#if defined(__linux__)
TEST(LargeArray, LargeArraysAreAdvisedAsHugePages)
{
    if (!std::ifstream("/sys/kernel/mm/transparent_hugepage/enabled"))
        GTEST_SKIP() << "this kernel has no transparent huge pages";
    LargeArray<float> state(std::size_t(6) << 20, 1.0f); // 24 MiB
    const std::string flags = mappingFlags(state.data());
    ASSERT_FALSE(flags.empty()) << "no mapping in /proc/self/smaps holds the array";
    EXPECT_NE(flags.find(" hg"), std::string::npos) << flags; // MADV_HUGEPAGE
}
#endif
