// A manifold carried over for a pair that has hardly moved: each carried point's separation
// against the narrow phase's own at the new poses (the same features, the same distance), and
// no carrying once the pair has moved further than kCarryDistance or looks further than before.
#include <gtest/gtest.h>

#include <numbers>
#include <random>

#include "core/contact/narrow_phase.hpp"
#include "core/rigid/carried_manifold.hpp"
#include "pba/forces.hpp"
#include "pba/world.hpp"

namespace {

using namespace pba::rigid;
using pba::dquat;
using pba::dvec3;
using pba::contact::CollisionShape;
using pba::contact::Transform;

struct Pose {
    dvec3 x{0.0};
    dquat q{1.0, 0.0, 0.0, 0.0};
    Transform transform() const { return {x, glm::mat3_cast(q)}; }
};

dquat turned(double degrees, const dvec3& axis)
{
    return glm::angleAxis(degrees * std::numbers::pi / 180.0, glm::normalize(axis));
}

/// The narrow phase's contact of a and b, as the rigid system keeps it.
Contact found(const CollisionShape& sa, const Pose& a, const CollisionShape& sb, const Pose& b, double margin)
{
    const pba::contact::Manifold m = pba::contact::collide(sa, a.transform(), sb, b.transform(), margin);
    Contact c;
    c.takePoints(m);
    c.found = pairPose(a.transform(), a.q, b.x, b.q, m.normal, margin);
    return c;
}

// A die tilted a little on a slab (the slab's top face the reference) and, the other way round,
// a slab's underside on a die: small moves of the die give the narrow phase's separations.
TEST(CarriedManifold, GivesTheNarrowPhasesSeparationsForTheSameFeatures)
{
    const CollisionShape slab = CollisionShape::of(pba::Shape::box({1.0, 0.2, 1.0}));
    const CollisionShape die = CollisionShape::of(pba::Shape::box({0.1, 0.1, 0.1}));
    std::mt19937 random(3);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    for (int round = 0; round < 50; ++round) {
        const bool dieOnTop = round % 2 == 0;
        Pose a, b;
        b.x = dvec3(0.1 * unit(random), dieOnTop ? 0.149 : -0.149, 0.1 * unit(random));
        b.q = turned(0.5 * unit(random), {unit(random), 1.0, unit(random)});
        const CollisionShape& sa = dieOnTop ? slab : die;
        const CollisionShape& sb = dieOnTop ? die : slab;
        if (!dieOnTop)
            std::swap(a, b); // the die is A, under the slab B
        const double margin = 0.01;
        const Contact before = found(sa, a, sb, b, margin);
        ASSERT_EQ(before.count, 4);
        // Move the pair by less than kCarryDistance, both bodies, in place and in turn.
        const double radius = sb.boundingRadius();
        Pose a2 = a, b2 = b;
        a2.x += dvec3(0.2, -0.1, 0.3) * unit(random); // the pair together: no relative motion
        b2.x += a2.x - a.x + dvec3(unit(random), unit(random), unit(random)) * (0.15 * kCarryDistance);
        b2.q = turned(0.25 * kCarryDistance / radius * 180.0 / std::numbers::pi, {unit(random), 1.0, 0.0}) * b2.q;
        Contact carried;
        ASSERT_TRUE(carryManifold(before, a2.transform(), a2.q, b2.transform(), b2.q, radius, margin, carried));
        const Contact fresh = found(sa, a2, sb, b2, margin);
        int matched = 0;
        for (int i = 0; i < carried.count; ++i)
            for (int j = 0; j < fresh.count; ++j)
                if (carried.points[i].id == fresh.points[j].id) {
                    // The reference face's plane distance is exact; the other way round the normal
                    // turns with A, not with the face, by at most the turn above.
                    EXPECT_NEAR(carried.points[i].separation, fresh.points[j].separation, dieOnTop ? 1e-12 : 2e-6);
                    ++matched;
                }
        EXPECT_EQ(matched, 4) << "round " << round;
    }
}

TEST(CarriedManifold, IsNotCarriedFurtherThanItsDistanceOrBeyondItsMargin)
{
    const CollisionShape die = CollisionShape::of(pba::Shape::box({0.1, 0.1, 0.1}));
    Pose a, b;
    b.x = dvec3(0.02, 0.1, 0.0);
    const Contact before = found(die, a, die, b, 0.01);
    ASSERT_EQ(before.count, 4);
    Contact carried;
    Pose moved = b;
    moved.x.x += 0.9 * kCarryDistance;
    EXPECT_TRUE(carryManifold(before, a.transform(), a.q, moved.transform(), moved.q, die.boundingRadius(), 0.01, carried));
    EXPECT_FALSE(carryManifold(before, a.transform(), a.q, moved.transform(), moved.q, die.boundingRadius(), 0.011, carried))
        << "a margin wider than the one it was found within";
    moved.x.x += 0.2 * kCarryDistance;
    EXPECT_FALSE(carryManifold(before, a.transform(), a.q, moved.transform(), moved.q, die.boundingRadius(), 0.01, carried));
    moved = b;
    moved.q = turned(1.1 * kCarryDistance / die.boundingRadius() * 180.0 / std::numbers::pi, {1.0, 0.0, 0.0});
    EXPECT_FALSE(carryManifold(before, a.transform(), a.q, moved.transform(), moved.q, die.boundingRadius(), 0.01, carried))
        << "a turn that moves B's furthest point by more";
    // Lifted by 1.5 mm within a margin of 1 mm: every point is left out.
    moved = b;
    moved.x.y += 0.0015;
    ASSERT_TRUE(carryManifold(before, a.transform(), a.q, moved.transform(), moved.q, die.boundingRadius(), 0.001, carried));
    EXPECT_EQ(carried.count, 0);
}

TEST(CarriedManifold, IsNotCarriedOverForABodyGivenANewShape)
{
    // A die resting on a fixed slab grows twice as tall where it stands: its pair has not moved,
    // but the old manifold (its old bottom face) must not be carried: the die is pushed up out
    // of the slab by the half height it gained, in the step (with the old one carried, it stays sunk
    // 5 cm).
    pba::World world;
    world.addForce(std::make_unique<pba::Gravity>(dvec3(0, -9.81, 0)));
    world.contactSettings().sleeping = false; // resting, awake, its pair carried step after step
    auto slab = std::make_unique<pba::RigidBody>(pba::Shape::box({2.0, 0.2, 2.0}), 1000.0);
    slab->setPos(dvec3(0, 1.0, 0));
    slab->setFixed(true);
    world.addBody(std::move(slab));
    auto die = std::make_unique<pba::RigidBody>(pba::Shape::box({0.1, 0.1, 0.1}), 600.0);
    die->setPos(dvec3(0, 1.15, 0));
    auto& body = static_cast<pba::RigidBody&>(world.addBody(std::move(die)));
    for (int step = 0; step < 200; ++step)
        world.step(0.005);
    ASSERT_NEAR(body.getPos().y, 1.15, 1e-3);
    body.setShape(pba::Shape::box({0.1, 0.2, 0.1}), 600.0);
    world.step(0.005);
    EXPECT_NEAR(body.getPos().y, 1.2, 1e-3) << "pushed out in the step";
}

} // namespace
