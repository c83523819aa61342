// The fixed-timestep clock against its definition: steps = floor(sum of clamped frame
// times / dt), the accumulator carries the remainder, the cap drops whole steps.
// Frame times and dt are dyadic rationals so the floating-point sums are exact and the
// oracle is exact too.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "pba/clock.hpp"
#include "support/special_values.hpp"

using namespace pba;

using pba::test::kInf;
using pba::test::kNaN;

TEST(FixedTimestepClock, TakesFloorOfAccumulatedTimeOverDt)
{
    const double dt = 1.0 / 128.0;
    FixedTimestepClock clock(dt, 0.25, 1000);
    std::mt19937 rng(7);
    std::uniform_int_distribution<int> ticks(1, 400); // frame times in 1/1024 s up to ~0.39 s
    double clampedSum = 0.0;
    std::int64_t steps = 0;
    for (int frame = 0; frame < 2000; ++frame) {
        const double frameTime = ticks(rng) / 1024.0;
        clampedSum += std::min(frameTime, 0.25);
        steps += clock.advance(frameTime);
        EXPECT_EQ(steps, static_cast<std::int64_t>(std::floor(clampedSum / dt)));
        EXPECT_GE(clock.alpha(), 0.0);
        EXPECT_LT(clock.alpha(), 1.0);
        EXPECT_EQ(clock.accumulator(), clampedSum - static_cast<double>(steps) * dt);
    }
}

TEST(FixedTimestepClock, ClampsLongFramesAgainstTheSpiralOfDeath)
{
    const double dt = 1.0 / 64.0;
    FixedTimestepClock clock(dt, 0.25, 1000);
    EXPECT_EQ(clock.advance(5.0), 16); // 0.25 / (1/64)
    EXPECT_EQ(clock.droppedTime(), 4.75);
    EXPECT_EQ(clock.alpha(), 0.0);
}

TEST(FixedTimestepClock, StepCapDropsWholeStepsAndKeepsAlphaBelowOne)
{
    const double dt = 1.0 / 1024.0;
    FixedTimestepClock clock(dt, 0.25, 10);
    const double frame = 102.5 / 1024.0;
    EXPECT_EQ(clock.advance(frame), 10);
    EXPECT_GE(clock.alpha(), 0.0);
    EXPECT_LT(clock.alpha(), 1.0);
    EXPECT_DOUBLE_EQ(clock.alpha(), 0.5);
    for (int i = 0; i < 100; ++i) {
        EXPECT_LE(clock.advance(0.25), 10);
        EXPECT_LT(clock.alpha(), 1.0);
    }
}

TEST(FixedTimestepClock, RejectsHostileFrameTimesWithoutChangingState)
{
    FixedTimestepClock clock(1.0 / 64.0);
    clock.advance(1.0 / 128.0);
    const double before = clock.accumulator();
    for (double bad : {0.0, -1.0, kNaN, kInf, -kInf}) {
        EXPECT_THROW(clock.advance(bad), std::invalid_argument) << bad;
        EXPECT_EQ(clock.accumulator(), before);
    }
    EXPECT_THROW(FixedTimestepClock(0.0), std::invalid_argument);
    EXPECT_THROW(FixedTimestepClock(0.01, -1.0), std::invalid_argument);
    EXPECT_THROW(FixedTimestepClock(0.01, 0.25, 0), std::invalid_argument);
}

TEST(FixedTimestepClock, ChangingDtKeepsTheFractionOfAStep)
{
    FixedTimestepClock clock(1.0 / 64.0);
    clock.advance(1.5 / 64.0);
    EXPECT_DOUBLE_EQ(clock.alpha(), 0.5);
    clock.setDt(1.0 / 16.0);
    EXPECT_DOUBLE_EQ(clock.alpha(), 0.5);
}

// The semi-fixed and variable clocks (frame_clock.hpp): what steps a frame takes.
#include "pba/frame_clock.hpp"

TEST(FrameSteps, SemiFixedTakesWholeStepsThenTheRest)
{
    // 1/60 s at dt 1/512: eight steps of dt, then one of the 0.00104 s left.
    const double dt = 1.0 / 512.0, frame = 1.0 / 60.0;
    const std::vector<double> steps = frameSteps(ClockKind::SemiFixed, dt, frame, 0.25);
    ASSERT_EQ(steps.size(), 9u);
    for (std::size_t k = 0; k < 8; ++k)
        EXPECT_EQ(steps[k], dt);
    EXPECT_NEAR(steps[8], frame - 8 * dt, 1e-15);
    EXPECT_LT(steps[8], dt);
}

TEST(FrameSteps, SemiFixedClampsAHitchAndNeverStepsLongerThanDt)
{
    const double dt = 1.0 / 128.0;
    const std::vector<double> steps = frameSteps(ClockKind::SemiFixed, dt, 2.0, 0.25);
    EXPECT_EQ(steps.size(), 32u); // 0.25 s of the 2 s frame, in whole steps of dt
    for (const double h : steps)
        EXPECT_EQ(h, dt);
}

TEST(FrameSteps, VariableTakesTheWholeFrameInOneStep)
{
    EXPECT_EQ(frameSteps(ClockKind::Variable, 0.01, 0.25, 0.25), std::vector<double>{0.25});
    EXPECT_EQ(frameSteps(ClockKind::Variable, 0.01, 2.0, 0.25), std::vector<double>{2.0}); // no clamp: its lesson
}

TEST(FrameSteps, RefusesTheFixedClockAndBadTimes)
{
    EXPECT_THROW(frameSteps(ClockKind::Fixed, 0.01, 0.1, 0.25), std::invalid_argument);
    EXPECT_THROW(frameSteps(ClockKind::Variable, 0.01, 0.0, 0.25), std::invalid_argument);
    EXPECT_THROW(frameSteps(ClockKind::SemiFixed, kNaN, 0.1, 0.25), std::invalid_argument);
    EXPECT_THROW(frameSteps(ClockKind::SemiFixed, 0.01, kInf, 0.25), std::invalid_argument);
}

TEST(FrameSteps, NamesRoundTrip)
{
    for (const ClockKind kind : kClockKinds)
        EXPECT_EQ(clockFromName(clockName(kind)), kind);
    EXPECT_FALSE(clockFromName("semi_fixed").has_value());
}

// Frames of 1/30, 1/60 and 1/144 s are not exact in binary, nor is a dt of 1/1000 s: summed
// plainly, 60 frames of 1/60 s hold a hair less than 1000 steps of 0.001 s and the clock ran
// 999. The clock's sum is compensated and a step that is short of dt by rounding alone (a
// billionth of it) is taken, so after k frames of 1/r s it has taken exactly floor(k q / r)
// steps of 1/q s, at every frame: the fixed clock's runs at any frame rate are then the same
// steps, to the bit.
TEST(FixedTimestepClock, TakesExactlyTheExpectedStepsAtEveryFrameOfCommonFrameRates)
{
    for (const std::uint64_t q : {1000u, 500u, 120u, 100u, 60u})
        for (const std::uint64_t r : {30u, 60u, 144u, 25u, 240u}) {
            FixedTimestepClock clock(1.0 / double(q));
            for (std::uint64_t k = 1; k <= 20 * r; ++k) {
                clock.advance(1.0 / double(r));
                ASSERT_EQ(clock.totalSteps(), k * q / r) << "dt 1/" << q << " s, frame 1/" << r << " s, frame " << k;
                ASSERT_GE(clock.alpha(), 0.0);
                ASSERT_LT(clock.alpha(), 1.0);
            }
        }
}
