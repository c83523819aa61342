#pragma once
// The clock that times each phase of a swarm's step for `pba bench --phases`. Private to
// src/core/swarms/swarm.cpp.
#include <chrono>
#include <cstdint>

#include "pba/swarm.hpp"
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#include <x86intrin.h>
#endif

namespace pba {

// Internal linkage, as when this lived in swarm.cpp: the one file that includes it.
namespace {

/// Adds the time since its last lap to a phase's total; does nothing without a SwarmPhaseTimes.
/// On x86-64 it reads the time-stamp counter, converted to nanoseconds with a rate measured
/// once against steady_clock: an instruction, where steady_clock::now() is a call, which
/// makes the compiler keep none of a loop's constants in vector registers across it (the
/// calling convention saves none of them). With steady_clock a timed step was a fifth to a
/// third slower than an untimed one, most of it charged to the short phases; with the counter
/// the difference is a few percent.
class PhaseClock {
public:
    explicit PhaseClock(SwarmPhaseTimes* times) : m_times(times)
    {
        if (!m_times)
            return;
        // The rate first: measured at the first lap instead, its 5 ms fell between that lap's
        // reading and the next, and were charged to the surface test of the first timed step.
        static_cast<void>(nanosecondsPerTick());
        m_last = now();
    }
    void lap(SwarmPhaseTimes::Phase phase)
    {
        if (!m_times)
            return;
        const std::uint64_t t = now();
        const std::uint64_t ticks = t > m_last ? t - m_last : 0; // cores' counters may differ a little
        const auto ns = static_cast<std::uint64_t>(static_cast<double>(ticks) * nanosecondsPerTick());
        m_times->nanoseconds[phase].fetch_add(ns, std::memory_order_relaxed);
        m_last = t;
    }

private:
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
    static std::uint64_t now() { return __rdtsc(); }
    /// The counter's rate, from 5 ms of steady_clock (the counter runs at a constant rate on
    /// every x86-64 CPU of the last fifteen years, whatever the core's clock).
    static double nanosecondsPerTick()
    {
        static const double rate = [] {
            const auto t0 = std::chrono::steady_clock::now();
            const std::uint64_t c0 = __rdtsc();
            auto t1 = t0;
            while (t1 - t0 < std::chrono::milliseconds(5))
                t1 = std::chrono::steady_clock::now();
            const std::uint64_t c1 = __rdtsc();
            const double ns = std::chrono::duration<double, std::nano>(t1 - t0).count();
            return c1 > c0 ? ns / static_cast<double>(c1 - c0) : 0.0; // a counter that stood still: no times
        }();
        return rate;
    }
#else
    static std::uint64_t now()
    {
        return static_cast<std::uint64_t>(std::chrono::duration_cast<std::chrono::nanoseconds>(
                                              std::chrono::steady_clock::now().time_since_epoch())
                                              .count());
    }
    static double nanosecondsPerTick() { return 1.0; }
#endif
    SwarmPhaseTimes* m_times;
    std::uint64_t m_last = 0;
};

} // namespace

} // namespace pba
