// The rounds a halved island's passes run in (src/core/rigid/halves.hpp): each round's Across job
// after both halves' jobs of that round, the next round's after it, and the rounds ending where
// an Across job says, on one thread as on two.
#include <gtest/gtest.h>

#include <mutex>
#include <vector>

#include <tbb/global_control.h>

#include "core/rigid/halves.hpp"

namespace {

using pba::rigid::Half;
using pba::rigid::runHalves;

struct Done {
    int round;
    Half half;
};

std::vector<Done> runRounds(int threads, int rounds, int endAfter)
{
    const tbb::global_control cores(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
    std::mutex m;
    std::vector<Done> order;
    runHalves(rounds, [&](int round, Half half) {
        const std::lock_guard lock(m);
        order.push_back({round, half});
        return !(half == Half::Across && round == endAfter);
    });
    return order;
}

TEST(Halves, EachRoundsCutAfterBothHalvesAndBeforeTheNextRound)
{
    for (int threads = 1; threads <= 2; ++threads) {
        const std::vector<Done> order = runRounds(threads, 50, 1000);
        ASSERT_EQ(order.size(), 150u) << threads << " threads";
        for (std::size_t k = 0; k < order.size(); ++k) {
            // Jobs finish in rounds: three of round r, in any order of the halves, the cut last.
            EXPECT_EQ(order[k].round, int(k / 3)) << threads << " threads, job " << k;
            if (k % 3 == 2) {
                EXPECT_EQ(order[k].half, Half::Across) << threads << " threads, job " << k;
            }
        }
    }
}

TEST(Halves, AnAcrossJobEndsTheRounds)
{
    for (int threads = 1; threads <= 2; ++threads) {
        const std::vector<Done> order = runRounds(threads, 50, 6);
        ASSERT_EQ(order.size(), 21u) << threads << " threads"; // rounds 0 to 6
        EXPECT_EQ(order.back().round, 6);
        EXPECT_EQ(order.back().half, Half::Across);
    }
}

TEST(Halves, AContactsPartIsItsBodiesHalfOrAcross)
{
    using pba::rigid::halfOf;
    EXPECT_EQ(halfOf(0, 0), Half::First);
    EXPECT_EQ(halfOf(1, 1), Half::Second);
    EXPECT_EQ(halfOf(0, 1), Half::Across);
    EXPECT_EQ(halfOf(1, -1), Half::Second); // on the floor: its body's half
    EXPECT_EQ(halfOf(-1, 0), Half::First);
    EXPECT_EQ(halfOf(-1, -1), Half::Across); // two static bodies: never solved, but somewhere
}

} // namespace
