#pragma once
// How the core shares work among cores: every loop split this way gives each index the same
// result whatever thread computes it, so a world's results do not depend on its thread count.
#include <cstddef>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "pba/force.hpp"

namespace pba::detail {

/// Runs fn on `threads` cores: 0 (or as many as there are) runs it in the default arena rather
/// than making a new one every step.
template <class F>
decltype(auto) onCores(int threads, F&& fn)
{
    if (threads <= 0 || threads >= tbb::this_task_arena::max_concurrency())
        return fn();
    tbb::task_arena arena(threads);
    return arena.execute(fn);
}

/// Indices a task: a few thousand (below that, starting a thread costs more than the work: a
/// rope's or a few particles' loop runs on the calling thread).
inline constexpr std::size_t kIndexGrain = 2048;

/// fn(i) for every i < n, `grain` indices a task (fewer where an index is more work).
template <class F>
void forEachIndex(std::size_t n, F&& fn, std::size_t grain = kIndexGrain)
{
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, grain), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t i = r.begin(); i < r.end(); ++i)
            fn(i);
    });
}

/// A force on one body at a time, for all of them: adds forceOn(i) to every moving body's
/// accumulator, on all cores (each body's sum is the same whichever thread computes it). The
/// built-in forces on one body (gravity, drag, the blow dryer) accumulate with it.
template <class F>
void addToEachMoving(const BodyStates& in, Accumulators& out, F&& forceOn)
{
    forEachIndex(in.bodies.size(), [&](std::size_t i) {
        if (in.moving(i))
            out.add(i, forceOn(i));
    });
}

} // namespace pba::detail
