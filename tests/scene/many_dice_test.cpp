// manyDice's throw: every die starts inside the room and apart from every other, whatever their
// orientations, and a die's start depends on its index alone.
#include <gtest/gtest.h>

#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

#include "pba/rigid_body.hpp"
#include "pba/scene/scene.hpp"
#include "pba/world.hpp"

using namespace pba;

namespace {

const RigidBody& die(const Scene& scene, std::size_t i) { return static_cast<const RigidBody&>(scene.world.body(i)); }

} // namespace

// Two boxes whose bounding spheres (radius: half the diagonal) do not meet cannot overlap in any
// orientation, nor can a box whose sphere lies inside the room reach a wall: checked over every
// pair of the fullest throw the room holds.
TEST(ManyDice, StartInsideTheRoomWithNoTwoOverlapping)
{
    const Scene scene = manyDice(10648);
    const Aabb room = *scene.world.room();
    const double radius = 0.5 * glm::length(dvec3(0.1));
    const std::size_t n = scene.world.bodyCount();
    ASSERT_EQ(n, 10648u);
    std::vector<dvec3> x(n);
    for (std::size_t i = 0; i < n; ++i) {
        x[i] = die(scene, i).getPos();
        ASSERT_TRUE(glm::all(glm::greaterThanEqual(x[i] - radius, room.min))) << i;
        ASSERT_TRUE(glm::all(glm::lessThanEqual(x[i] + radius, room.max))) << i;
    }
    // Every pair closer than a diameter along x, found by sweeping the dice in order of x.
    std::sort(x.begin(), x.end(), [](const dvec3& a, const dvec3& b) { return a.x < b.x; });
    for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = i + 1; j < n && x[j].x - x[i].x < 2.0 * radius; ++j) {
            const dvec3 d = x[j] - x[i];
            if (glm::dot(d, d) < 4.0 * radius * radius)
                FAIL() << "dice at " << x[i].x << ", " << x[i].y << ", " << x[i].z << " and " << x[j].x << ", "
                       << x[j].y << ", " << x[j].z << " are " << glm::length(d) << " m apart";
        }
}

// The first dice of a small throw are the first dice of a large one, and the throw fills the room
// from the first dice on (not its floor first): a die's place, turn, velocity and spin are its own.
TEST(ManyDice, ADiesStartDependsOnItsIndexAlone)
{
    const Scene few = manyDice(100), many = manyDice(5000);
    dvec3 lo(1e9), hi(-1e9);
    for (std::size_t i = 0; i < few.world.bodyCount(); ++i) {
        const RigidBody &a = die(few, i), &b = die(many, i);
        EXPECT_EQ(a.getPos(), b.getPos()) << i;
        EXPECT_EQ(a.getVel(), b.getVel()) << i;
        EXPECT_EQ(a.getOrientation(), b.getOrientation()) << i;
        EXPECT_EQ(a.getAngularMomentum(), b.getAngularMomentum()) << i;
        lo = glm::min(lo, a.getPos());
        hi = glm::max(hi, a.getPos());
    }
    const Aabb room = *few.world.room();
    EXPECT_TRUE(glm::all(glm::greaterThan(hi - lo, 0.8 * (room.max - room.min)))) << hi.y - lo.y;
}

// More dice than the room's cells is refused, naming the limit.
TEST(ManyDice, MoreDiceThanTheRoomHoldsAreRefused)
{
    EXPECT_THROW(manyDice(0), std::invalid_argument);
    try {
        manyDice(10649);
        FAIL() << "no error";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("at most 10648 dice"), std::string::npos) << e.what();
    }
}
