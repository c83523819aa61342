#pragma once
// What every phase of a swarm's step shares: the block of particles it works on (its size, the
// rows of its start states, the arrays it steps), the test of whether the states a loop wrote
// are finite, and the listing of a block's marked particles. Private to src/core/swarms/swarm.cpp, the
// one file that includes it (with swarm_integrate.hpp and swarm_collide.hpp), so that every
// instruction set's copy of the step (PBA_FOR_EACH_INSTRUCTION_SET) inlines all of it.
#include <algorithm>
#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>

#include "pba/detail/instruction_sets.hpp"
#include "pba/swarm.hpp"

namespace pba {

// Internal linkage, as when this lived in swarm.cpp: the one file that includes it.
namespace {

/// Particles a block: the start states of one block stay in L1 while the block is stepped, in
/// six rows of kBlock floats (rows 192 bytes longer, against 4K aliasing between them, measured
/// no faster on a quiet machine: docs/performance.md).
constexpr std::size_t kBlock = 512;
/// A block with at most this many particles at a surface has them gathered, with those of other
/// such blocks, for the collision rule (GatheredHits), padded to whole vectors of kGatherWidth
/// floats (AVX-512's 16).
constexpr std::size_t kGatherMax = 64;
constexpr std::size_t kGatherWidth = 16;

/// Where the steps of a block's particles began: three rows, x, y and z.
using StartPositions = std::array<const float*, 3>;

struct Arrays {
    float *px, *py, *pz, *vx, *vy, *vz;
    std::uint8_t* clear; ///< 1: the position is clear of every surface (known from the last step)
    std::uint8_t* finite; ///< per block: 1 when its six arrays are all finite after the step
    std::uint8_t* crowded; ///< per block: 1 when the collision pass moved most of it last step
    std::uint8_t* blowing; ///< per block: steps before the dryer's split is tried again (integrateInDryer)
    SwarmPhaseTimes* phases = nullptr; ///< where to add each phase's time, if anywhere
};

/// The exponent field of f: all ones (kSpecialExponent) exactly when f is an infinity or a NaN.
/// A loop keeps the largest it sees, an unsigned maximum (one instruction a vector, where
/// comparing each and ORing the result into a flag took three; a float sum would not vectorise
/// without reassociation), and tests it once at the end.
constexpr std::uint32_t kSpecialExponent = 0x7f800000u;
inline std::uint32_t exponentField(float f)
{
    std::uint32_t bits;
    std::memcpy(&bits, &f, sizeof bits);
    return bits & kSpecialExponent;
}

/// The exponent field of the sum of the state's six components: special whenever a component
/// is; a finite state whose sum overflows only sends Swarm::findNonFinite to look for nothing.
inline std::uint32_t exponentOfSum(const Vec3<float>& x, const Vec3<float>& v)
{
    return exponentField(x.x + x.y + x.z + v.x + v.y + v.z);
}

/// The particles of a block marked in `hit`, listed in `index` (room for all that are marked);
/// returns how many, and in `spare` the first clear one. The flags are first packed
/// eight to a byte (a multiplication gathers eight 0/1 bytes into eight bits: one loop, which
/// vectorises), and the scan then visits only the set bits of each 64: a branch a word and one
/// a hit, where a branch every eight flags mispredicted often. `hit` has room for a whole
/// last word of 64.
std::size_t listHits(std::uint8_t* __restrict hit, std::size_t n, std::uint16_t* __restrict index,
                     std::size_t& spare)
{
    std::fill(hit + n, hit + (n + 63) / 64 * 64, std::uint8_t(0));
    alignas(64) std::uint8_t packed[kBlock / 8]; // byte w: flags 8w to 8w + 7, little-endian
    const std::size_t words = (n + 63) / 64;
    for (std::size_t w = 0; w < words * 8; ++w) {
        std::uint64_t eight;
        std::memcpy(&eight, hit + 8 * w, sizeof eight);
        packed[w] = static_cast<std::uint8_t>(eight * 0x0102040810204080ull >> 56); // byte i's bit 0 to bit i
    }
    std::size_t m = 0;
    spare = n;
    for (std::size_t q = 0; q < words; ++q) {
        std::uint64_t bits;
        std::memcpy(&bits, packed + 8 * q, sizeof bits);
        if (spare == n && ~bits != 0) // the first clear one (before any padding: some are clear)
            spare = 64 * q + static_cast<std::size_t>(std::countr_one(bits));
        for (; bits != 0; bits &= bits - 1)
            index[m++] = static_cast<std::uint16_t>(64 * q + static_cast<std::size_t>(std::countr_zero(bits)));
    }
    return m;
}

} // namespace

} // namespace pba
