#pragma once
// `pba bench --pile-worker`: manyDice's throw stepped on all cores, a window of steps at a time on
// request, for bench/peers/pile.py, which takes its windows in turn with the Bullet peer's
// (bench/peers/bullet_pile.cpp) and checks both piles' final states.
#include <cstddef>
#include <cstdint>
#include <filesystem>

#include "pba/world.hpp"

namespace pba::app::bench {

/// An order-free checksum of a pile's state: the sum, modulo 2^64, of the 13 numbers of every die
/// (x, y, z, qw, qx, qy, qz, vx, vy, vz, wx, wy, wz, the angular velocity in the world frame)
/// rounded to float and read as 32-bit integers. A peer that read writePileState's file and
/// rounds the same numbers to its own float gets the same sum only if it read every one of them.
std::uint64_t pileStateBits(const World& world);

/// The world's dice as CSV, one row each: name,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz (SI units;
/// the orientation as a unit quaternion, body to world; the angular velocity in the world frame),
/// each number as the shortest text that reads back as the same double. Written whole or not at
/// all (AtomicFile).
void writePileState(const World& world, const std::filesystem::path& path);

/// The worker: manyDice(dice) on all cores, its steps driven line by line from standard input:
///   window STEPS   step on STEPS steps from where the last window ended; print
///                  {"seconds", "steps", "t", "steps_per_s"}
///   save PATH      write the current state (writePileState); print {"saved", "t"}
/// Each answer is one JSON line; the first, {"ready": ...}, gives what a peer needs to build the
/// same pile: the dice count, dt, gravity, the room, a die's size, mass, inertia (its diagonal,
/// body frame), friction and restitution, and pileStateBits of the start.
int runPileWorker(std::size_t dice, int iterations);

/// The pile's solver, compared sweep for sweep with a peer's: `iterations` velocity sweeps every
/// step, a fixed count (Bullet's default is 10), rather than pba's sweeps to convergence.
inline constexpr int kPileIterations = 10;
void usePileSolver(World& world, int iterations);

} // namespace pba::app::bench
