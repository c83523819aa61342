// The broad phase against a test of every pair: the grid must find each overlapping pair with an
// awake body exactly once, whatever mix of sizes, sleeping, fixed and point bodies the world has
// (a board of fixed pegs is in the grid; a floor slab larger than a cell is not).
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "core/rigid/broad_phase.hpp"

namespace {

using namespace pba::rigid;
using pba::dvec3;

std::vector<BodyPair> everyPair(const std::vector<Box>& boxes, const std::vector<Motion>& motion,
                                const std::vector<std::uint8_t>& isPoint)
{
    std::vector<BodyPair> pairs;
    for (std::size_t i = 0; i < boxes.size(); ++i)
        for (std::size_t j = i + 1; j < boxes.size(); ++j)
            if (boxes[i].overlaps(boxes[j]) && (motion[i] == Motion::Awake || motion[j] == Motion::Awake) &&
                !(isPoint[i] && isPoint[j]))
                pairs.push_back({BodyIndex(i), BodyIndex(j)});
    return pairs;
}

TEST(BroadPhase, FindsEveryOverlappingPairWithAnAwakeBodyOnce)
{
    std::mt19937 random(7);
    std::uniform_real_distribution<double> where(-2.0, 2.0), size(0.05, 0.3), kind(0.0, 1.0);
    for (int round = 0; round < 20; ++round) {
        std::vector<Box> boxes;
        std::vector<Motion> motion;
        std::vector<std::uint8_t> isPoint;
        for (int k = 0; k < 400; ++k) {
            const double u = kind(random);
            const dvec3 at(where(random), where(random), where(random));
            // Fixed pegs, a few fixed slabs wider than any cell, dice awake and asleep, and points.
            const bool slab = u < 0.01, peg = u < 0.3, point = u > 0.85;
            const dvec3 half = point ? dvec3(0.01) : slab ? dvec3(3.0, 0.1, 3.0) : dvec3(size(random), size(random), size(random));
            boxes.push_back({at - half, at + half});
            motion.push_back(slab || peg ? Motion::Static : u < 0.45 ? Motion::Asleep : Motion::Awake);
            isPoint.push_back(point);
        }
        BroadPhase broad;
        std::vector<BodyPair> found;
        broad.findPairs(boxes, motion, isPoint, found);
        EXPECT_EQ(found, everyPair(boxes, motion, isPoint)) << "round " << round;
    }
}

} // namespace
