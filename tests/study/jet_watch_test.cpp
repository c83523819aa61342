// JetWatch's figures for a swarm against a plain count: a counter per particle, kept every step.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

#include "pba/scene/scene.hpp"
#include "study/jet_watch.hpp"

namespace pba::study {
namespace {

/// blow-dryer-swarm with `count` of its particles: three of the watch's segments for 20,000.
Scene rainOf(std::size_t count)
{
    Scene scene = loadScene("blow-dryer-swarm");
    SwarmDesc desc = scene.world.swarm(0).desc();
    desc.count = count;
    scene.world.swarm(0) = Swarm(desc);
    return scene;
}

// The watch lists only the particles under the hole, a segment of 8,192 at a time on all cores;
// the oracle counts, for every particle, its steps in a row there (inBlowDryerShaft in floats, as the swarm's kernel has it). Over
// blow-dryer-swarm's first 8 s with 20,000 of its particles (about 9,000 stays under the hole,
// the longest 53 steps) the longest stay is the same number of steps.
TEST(JetWatch, ASwarmsLongestStayUnderTheHoleIsThePlainCounts)
{
    Scene scene = rainOf(20000);
    World& world = scene.world;
    JetWatch watch(world);
    const BlowDryerKernelT<float> kernel(watch.field().as<float>());
    std::vector<std::uint32_t> steps(world.swarm(0).size(), 0);
    std::uint32_t longest = 0;
    std::size_t entered = 0;
    for (long n = 0; n < std::lround(8.0 / scene.dt); ++n) {
        world.step(scene.dt);
        watch.record(world);
        const Swarm& swarm = world.swarm(0);
        for (std::size_t i = 0; i < swarm.size(); ++i) {
            const DryerFrameT<DryerAxis::Up, float> frame(kernel.nozzle, kernel.axis, swarm.position(i));
            const bool in = inBlowDryerShaft(kernel, frame.d.y, frame.across2);
            entered += in && steps[i] == 0 ? 1 : 0;
            steps[i] = in ? steps[i] + 1 : 0;
            longest = std::max(longest, steps[i]);
        }
    }
    EXPECT_GT(entered, 100u) << "the run should send particles through the hole";
    EXPECT_GT(longest, 1u);
    EXPECT_DOUBLE_EQ(watch.swarms().at(0).longestInShaft, double(longest) * (world.time() - world.previousTime()));
}

// The cone's count, every 0.1 s: a test in floats picks the particles that take the exact one in
// double, on all cores. Its peak and when are the plain count's: insideBlowDryerCone for every
// particle at the same times (blow-dryer-swarm's first 3 s, 20,000 particles: three segments,
// the rain falling through the cone and landing around it).
TEST(JetWatch, ASwarmsPeakInTheConeIsThePlainCount)
{
    Scene scene = rainOf(20000);
    World& world = scene.world;
    JetWatch watch(world);
    std::size_t peak = 0;
    double peakAt = 0.0, nextLook = 0.0;
    const auto look = [&] {
        if (world.time() < nextLook - 1e-9)
            return;
        nextLook = world.time() + JetWatch::kSwarmSample;
        std::size_t count = 0;
        for (std::size_t i = 0; i < world.swarm(0).size(); ++i)
            count += insideBlowDryerCone(watch.field(), dvec3(world.swarm(0).position(i))) ? 1 : 0;
        if (count > peak)
            peak = count, peakAt = world.time();
    };
    look();
    for (long n = 0; n < std::lround(3.0 / scene.dt); ++n) {
        world.step(scene.dt);
        watch.record(world);
        look();
    }
    EXPECT_GT(peak, 1000u) << "the rain should fall through the cone";
    EXPECT_EQ(watch.swarms().at(0).peakInCone, peak);
    EXPECT_EQ(watch.swarms().at(0).peakAt, peakAt);
}

// Attached (as pba sim watches), the lists are made range by range inside the swarm's step; the
// figures are those of the watch's own pass, on 1 and 2 threads, with 40,000 particles (over the
// swarm's threshold for splitting its step) through blow-dryer-swarm's first 3 s.
TEST(JetWatch, AttachedItListsTheSameStaysInsideTheStep)
{
    for (const int threads : {1, 2}) {
        Scene scene = rainOf(40000);
        scene.world.setThreads(threads);
        World alone = scene.world;
        JetWatch watch(scene.world), plain(alone);
        {
            const JetWatch::Attachment attached = watch.attach(scene.world);
            for (long n = 0; n < std::lround(3.0 / scene.dt); ++n) {
                scene.world.step(scene.dt);
                watch.record(scene.world);
                alone.step(scene.dt);
                plain.record(alone);
            }
        }
        EXPECT_EQ(watch.stepsListedInStep(), std::uint64_t(std::lround(3.0 / scene.dt)));
        EXPECT_EQ(plain.stepsListedInStep(), 0u);
        EXPECT_GT(plain.swarms().at(0).longestInShaft, 0.0) << "the run should send particles through the hole";
        EXPECT_EQ(watch.swarms().at(0).longestInShaft, plain.swarms().at(0).longestInShaft) << threads << " threads";
        EXPECT_EQ(watch.swarmsInShaft(scene.world), plain.swarmsInShaft(alone));
        // Detached, the watch makes its lists itself again.
        scene.world.step(scene.dt);
        watch.record(scene.world);
        alone.step(scene.dt);
        plain.record(alone);
        EXPECT_EQ(watch.swarms().at(0).longestInShaft, plain.swarms().at(0).longestInShaft);
        EXPECT_EQ(watch.stepsListedInStep(), std::uint64_t(std::lround(3.0 / scene.dt)));
    }
}

// A body's mean distance from the axis while in the cone: a fixed ball 0.3 m off the axis
// reads 0.3 to rounding, one on it 0; a body never in the cone has none.
TEST(JetWatch, ABodysMeanDistanceFromTheAxisIsWhereItIsInTheCone)
{
    Scene scene = parseScene(R"({"dt": 0.01, "duration": 1, "room": {"min": [-3, 0, -3], "max": [3, 4, 3]},
        "particles": [{"name": "off", "position": [0.3, 2, 0], "fixed": true},
                      {"name": "on", "position": [0, 1.5, 0], "fixed": true},
                      {"name": "out", "position": [2.5, 0.5, 0], "fixed": true}],
        "forces": [{"type": "blow-dryer", "nozzle": [0, 0, 0], "height": 3.5, "top_radius": 1.2, "strength": 30}]})",
                             "axis.json");
    JetWatch watch(scene.world);
    for (int n = 0; n < 50; ++n) {
        scene.world.step(scene.dt);
        watch.record(scene.world);
    }
    const std::vector<BodyInJet> bodies = watch.bodies();
    EXPECT_NEAR(bodies[0].meanOffAxisInCone, 0.3, 1e-12);
    EXPECT_EQ(bodies[1].meanOffAxisInCone, 0.0);
    EXPECT_TRUE(std::isnan(bodies[2].meanOffAxisInCone));
}

} // namespace
} // namespace pba::study
