#pragma once
// A huge island's passes on two cores without a fork and join a sweep: its moving bodies are cut
// in two halves in space, and each round of a pass (one sweep) solves the contacts within each
// half at once, then the few across the cut. Whoever is free takes the next job in order and
// waits only for the jobs it follows; a thread alone takes them all, in the same order of
// dependencies, so the results are the same on any number of threads. A fork and join a sweep
// (or a colour) cost more on two cores than the sweep saved: the other core had to be woken and
// the bodies' lines moved between the cores' caches for every colour.
// Private to the core.
#include <atomic>
#include <cstdint>
#include <memory>
#include <thread>

#include <tbb/parallel_invoke.h>
#include <tbb/task_arena.h>

namespace pba::rigid {

/// Which part of a halved island a contact belongs to.
enum class Half : std::uint8_t { First = 0, Second = 1, Across = 2 };

/// The part of a contact between bodies on sides sa and sb (0 or 1, or -1 for a static body).
inline Half halfOf(int sa, int sb)
{
    const int side = sa < 0 ? sb : sb < 0 ? sa : sa == sb ? sa : 2;
    return side < 0 ? Half::Across : Half(side);
}

/// Runs up to `rounds` rounds of job(round, half): each round's First and Second at once, then
/// its Across, then the next round. Across returns false to end the rounds after its own.
template <class Job>
void runHalves(int rounds, Job&& job)
{
    if (rounds <= 0)
        return;
    const int jobs = 3 * rounds;
    std::unique_ptr<std::atomic<std::uint8_t>[]> done(new std::atomic<std::uint8_t>[std::size_t(jobs)]);
    for (int k = 0; k < jobs; ++k)
        done[k].store(0, std::memory_order_relaxed);
    std::atomic<int> next{0}, last{rounds};
    const auto waitFor = [&](int k) {
        for (int spins = 0; !done[k].load(std::memory_order_acquire); ++spins)
            if (spins > 64)
                std::this_thread::yield(); // the job's thread may have lost its core
    };
    const auto work = [&] {
        for (int k = next.fetch_add(1); k < jobs; k = next.fetch_add(1)) {
            const int round = k / 3;
            const Half half = Half(k % 3);
            if (half == Half::Across) {
                waitFor(k - 2);
                waitFor(k - 1);
            } else if (round > 0) {
                waitFor(3 * round - 1);
            }
            // Past the last round: nothing to do, but marked done for whoever waits on it.
            if (round < last.load(std::memory_order_acquire) && !job(round, half) && half == Half::Across)
                last.store(round + 1, std::memory_order_release);
            done[k].store(1, std::memory_order_release);
        }
    };
    // Isolated: a thread waiting here takes no other island's work, whose scratch it holds.
    tbb::this_task_arena::isolate([&] { tbb::parallel_invoke(work, work); });
}

} // namespace pba::rigid
