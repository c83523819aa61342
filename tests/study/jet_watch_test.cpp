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

// The watch lists only the particles under the hole; the oracle counts, for every particle,
// its steps in a row there (inBlowDryerShaft in floats, as the swarm's kernel has it). Over
// blow-dryer-swarm's first 8 s with 20,000 of its particles (about 9,000 stays under the hole,
// the longest 53 steps) the longest stay is the same number of steps.
TEST(JetWatch, ASwarmsLongestStayUnderTheHoleIsThePlainCounts)
{
    Scene scene = loadScene("blow-dryer-swarm");
    SwarmDesc desc = scene.world.swarm(0).desc();
    desc.count = 20000;
    scene.world.swarm(0) = Swarm(desc);
    World& world = scene.world;
    JetWatch watch(world);
    const BlowDryerKernelT<float> kernel(watch.field().as<float>());
    std::vector<std::uint32_t> steps(desc.count, 0);
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

} // namespace
} // namespace pba::study
