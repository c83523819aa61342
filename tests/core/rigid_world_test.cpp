// Rigid bodies in the World against exact results: a box dropped flat rebounds to e^2 h without
// turning, a sliding ball starts to roll when and as fast as the closed form says, a tilted box
// settles on a face and stays there, nothing leaves the room however fast it is thrown, a free
// body's tumble in the World is the rotation integrator's, and a bouncing contact is told from a
// resting one by a flag, not by its target speed.
#include "pba/world.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>
#include <vector>

#include "pba/blow_dryer.hpp"
#include "pba/forces.hpp"
#include "pba/scene/scene.hpp"

#include "rigid/contact_solver.hpp"

using namespace pba;

namespace {

constexpr double kG = 9.81;

World roomWorld(double gravity = kG)
{
    World world;
    world.setRoom(Aabb{dvec3(-2.0, 0.0, -2.0), dvec3(2.0, 4.0, 2.0)});
    if (gravity != 0.0)
        world.addForce(std::make_unique<Gravity>(dvec3(0.0, -gravity, 0.0)));
    return world;
}

RigidBody& addRigid(World& world, const Shape& shape, double density, const dvec3& position)
{
    auto body = std::make_unique<RigidBody>(shape, density);
    body->setPos(position);
    return static_cast<RigidBody&>(world.addBody(std::move(body)));
}

/// The lowest of the body's contact points (a sphere's bottom), world frame.
double lowestPoint(const RigidBody& b)
{
    if (b.getShape().type == ShapeType::Sphere)
        return b.getPos().y - b.getShape().radius;
    const dmat3 r = glm::mat3_cast(b.getOrientation());
    double low = 1e300;
    for (const dvec3& p : b.getContactPoints())
        low = std::min(low, (b.getPos() + r * p).y);
    return low;
}

} // namespace

TEST(RigidWorld, ImplicitGyroscopicIsANamedIntegrator)
{
    EXPECT_EQ(integratorFromName("implicit-gyroscopic"), Integrator::ImplicitGyroscopic);
    EXPECT_EQ(integratorName(Integrator::ImplicitGyroscopic), "implicit-gyroscopic");
    EXPECT_EQ(translationalMethod(Integrator::ImplicitGyroscopic), Integrator::SemiImplicitEuler);
}

TEST(RigidWorld, BoxDroppedFlatReboundsToESquaredHWithoutTurning)
{
    for (const auto& [e, integrator] : {std::pair{1.0, Integrator::SemiImplicitEuler}, std::pair{0.5, Integrator::SemiImplicitEuler},
                                       std::pair{0.5, Integrator::RK4}, std::pair{0.5, Integrator::VelocityVerlet},
                                       std::pair{0.5, Integrator::ForwardEuler}, std::pair{0.5, Integrator::ImplicitGyroscopic}}) {
        World world = roomWorld();
        const double h = 1.0;
        const dvec3 size(0.4, 0.2, 0.3);
        RigidBody& box = addRigid(world, Shape::box(size), 500.0, dvec3(0.3, h + 0.5 * size.y, -0.2));
        box.setCor(e);
        box.setIntegrator(integrator);
        const double dt = 0.0005;
        bool bounced = false;
        double apex = 0.0, maxOmega = 0.0;
        for (int n = 0; n < int(3.0 / dt); ++n) {
            const double before = box.getVel().y;
            world.step(dt);
            bounced = bounced || (before < 0.0 && box.getVel().y > 0.0);
            if (bounced && box.getVel().y < 0.0 && apex > 0.0)
                break; // past the apex of the rebound
            if (bounced)
                apex = std::max(apex, lowestPoint(box));
            maxOmega = std::max(maxOmega, glm::length(box.getAngularVelocity()));
        }
        ASSERT_TRUE(bounced);
        EXPECT_NEAR(apex, e * e * h, 0.02 * e * e * h) << "e = " << e << ", " << integratorName(integrator);
        EXPECT_LT(maxOmega, 1e-6) << "e = " << e << ", " << integratorName(integrator);
    }
}

TEST(RigidWorld, ASmallBoxFallsThroughTheFloorHoleAndRestsOnTheGrilleInsideTheShaft)
{
    World world = roomWorld();
    world.setFloorHole(FloorHole{dvec3(0.0), 0.3, 0.5});
    RigidBody& box = addRigid(world, Shape::box(dvec3(0.2, 0.1, 0.15)), 500.0, dvec3(0.0, 1.0, 0.0));
    box.setVel(dvec3(0.25, 0.0, 0.1)); // into the hole, and on into the shaft's wall
    box.setAngularVelocity(dvec3(1.0, 2.0, 0.5));
    box.setCor(0.3);
    for (int n = 0; n < 3000; ++n) {
        world.step(0.002);
        const dmat3 r = glm::mat3_cast(box.getOrientation());
        for (const dvec3& p : box.getContactPoints()) {
            const dvec3 at = box.getPos() + r * p;
            if (at.y < -kG * 0.002 * 0.002) { // below the floor: in the shaft
                ASSERT_LE(std::hypot(at.x, at.z), 0.3 + kG * 0.002 * 0.002) << "step " << n;
            }
            ASSERT_GE(at.y, -0.5 - kG * 0.002 * 0.002) << "step " << n;
        }
    }
    EXPECT_NEAR(lowestPoint(box), -0.5, 1e-3); // on the grille
    EXPECT_LT(glm::length(box.getVel()), 1e-3);
}

TEST(RigidWorld, SlidingBallStartsToRollAtTheClosedFormTimeAndSpeed)
{
    World world = roomWorld();
    const double r = 0.1, mu = 0.2, v0 = 2.0;
    RigidBody& ball = addRigid(world, Shape::sphere(r), 1000.0, dvec3(-1.5, r, 0.0));
    ball.setVel(dvec3(v0, 0.0, 0.0));
    ball.setFriction(mu);
    ball.setCor(0.0);
    const double dt = 0.0002;
    const double tRoll = 2.0 * v0 / (7.0 * mu * kG);
    double rolledAt = -1.0;
    for (int n = 0; n < int(1.0 / dt); ++n) {
        world.step(dt);
        // Rolling: the contact point at rest, v = omega x (0, -r, 0) ... i.e. v_x = omega_z * -r.
        const double slip = ball.getVel().x + ball.getAngularVelocity().z * r;
        if (rolledAt < 0.0 && std::abs(slip) < 1e-6 * v0)
            rolledAt = world.time();
    }
    ASSERT_GT(rolledAt, 0.0);
    EXPECT_NEAR(rolledAt, tRoll, 0.01 * tRoll);
    EXPECT_NEAR(ball.getVel().x, 5.0 / 7.0 * v0, 0.01 * 5.0 / 7.0 * v0);
    EXPECT_NEAR(ball.getPos().y, r, 1e-3);
}

TEST(RigidWorld, TiltedBoxSettlesOnAFaceWithoutGainingEnergySinkingOrCreeping)
{
    World world = roomWorld();
    RigidBody& box = addRigid(world, Shape::box(dvec3(0.3, 0.2, 0.25)), 500.0, dvec3(0.0, 0.6, 0.0));
    box.setOrientation(glm::angleAxis(0.5, glm::normalize(dvec3(1.0, 0.3, 0.7))));
    box.setCor(0.4);
    box.setFriction(0.6);
    const double dt = 0.002;
    double worst = 0.0, deepest = 0.0;
    for (int n = 0; n < int(5.0 / dt); ++n) {
        const double before = world.energy(0);
        world.step(dt);
        // In flight an explicit method's rotation changes a tumbling box's energy by itself (the
        // rigid-body study measures that); here only the steps that end in contact count.
        if (lowestPoint(box) < 1e-9) {
            worst = std::max(worst, world.energy(0) - before);
        }
        deepest = std::min(deepest, lowestPoint(box));
    }
    EXPECT_LE(worst, 1e-9) << "energy rose in a step";
    EXPECT_GT(deepest, -1e-3) << "sank";
    // At rest on a face: one of the box's axes vertical, then 10 s without moving.
    const dvec3 settled = box.getPos();
    const dquat q = box.getOrientation();
    for (int n = 0; n < int(10.0 / dt); ++n)
        world.step(dt);
    EXPECT_LT(glm::length(box.getPos() - settled), 1e-3);
    EXPECT_LT(glm::length(box.getVel()), 1e-6);
    EXPECT_NEAR(std::abs(glm::dot(q, box.getOrientation())), 1.0, 1e-9);
    const dmat3 r = glm::mat3_cast(box.getOrientation());
    double upright = 0.0;
    for (int axis = 0; axis < 3; ++axis)
        upright = std::max(upright, std::abs(r[axis].y));
    EXPECT_NEAR(upright, 1.0, 1e-6);
}

TEST(RigidWorld, NothingLeavesTheRoomAtFiftyMetresAndTwentyRadiansPerSecond)
{
    World world = roomWorld();
    const std::vector<Shape> shapes{Shape::box(dvec3(0.3, 0.2, 0.5)), Shape::sphere(0.2), Shape::cylinder(0.15, 0.4)};
    for (std::size_t k = 0; k < 9; ++k) {
        RigidBody& b = addRigid(world, shapes[k % 3], 700.0, dvec3(-1.0 + 0.25 * double(k), 2.0, 0.1 * double(k)));
        const double a = 0.7 * double(k);
        b.setVel(50.0 * glm::normalize(dvec3(std::cos(a), std::sin(1.3 * a), std::sin(a))));
        b.setAngularVelocity(20.0 * glm::normalize(dvec3(std::sin(a), 1.0, std::cos(a))));
        b.setCor(0.9);
    }
    // A point may end a step below the floor by what one step of gravity sinks a body at rest
    // (g dt^2, 4 mm here: the room's push-out takes back what is left beyond a wall), never further, and never out through a wall.
    const double dt = 0.02, allowed = kG * dt * dt;
    for (int n = 0; n < 500; ++n) {
        world.step(dt);
        for (std::size_t i = 0; i < world.bodyCount(); ++i) {
            const auto& b = static_cast<const RigidBody&>(world.body(i));
            const dmat3 r = glm::mat3_cast(b.getOrientation());
            std::vector<dvec3> points;
            if (b.getShape().type == ShapeType::Sphere)
                for (int axis = 0; axis < 3; ++axis)
                    for (const double side : {-1.0, 1.0}) {
                        dvec3 u(0.0);
                        u[axis] = side * b.getShape().radius;
                        points.push_back(b.getPos() + u);
                    }
            for (const dvec3& p : b.getContactPoints())
                points.push_back(b.getPos() + r * p);
            for (const dvec3& p : points)
                for (int axis = 0; axis < 3; ++axis) {
                    ASSERT_GE(p[axis], (axis == 1 ? 0.0 : -2.0) - allowed) << "body " << i << " step " << n;
                    ASSERT_LE(p[axis], (axis == 1 ? 4.0 : 2.0) + allowed) << "body " << i << " step " << n;
                }
        }
    }
}

// A spin turns a body within its bounding sphere: a box spun at 2,000 rad/s, 4 rad a step,
// whose sphere stays 7 cm clear of the floor meets nothing, where the floor's speculative
// contact, linear in the spin, used to kick it up at 83 m/s.
TEST(RigidWorld, AFastSpinMeetsNoWallItsBoundingSphereDoesNotReach)
{
    World world = roomWorld(0.0);
    RigidBody& box = addRigid(world, Shape::box(dvec3(0.2)), 1000.0, dvec3(0.0, 0.4, 0.0));
    box.setAngularVelocity(dvec3(0.0, 0.0, 2000.0));
    const double spin = box.getRotationalKineticEnergy();
    for (int n = 0; n < 10; ++n) {
        world.step(0.002);
        ASSERT_EQ(box.getVel(), dvec3(0.0)) << n;
        ASSERT_NEAR(box.getRotationalKineticEnergy(), spin, 1e-9 * spin) << n;
    }
}

TEST(RigidWorld, FreeTumbleInTheWorldIsTheRotationIntegrators)
{
    World world = roomWorld(0.0);
    const Shape shape = Shape::box(dvec3(0.1, 0.4, 0.25));
    RigidBody& b = addRigid(world, shape, 800.0, dvec3(0.0, 2.0, 0.0));
    b.setAngularVelocity(dvec3(0.01, 6.0, 0.02));
    b.setIntegrator(Integrator::RK4);
    Rotation alone = b.getRotation();
    const dmat3 inverse = b.getInverseInertiaBody();
    for (int n = 0; n < 500; ++n) {
        world.step(0.002);
        integrateRotation(Integrator::RK4, alone, inverse, 0.002, [](const dquat&, const dvec3&) { return dvec3(0.0); });
    }
    // The same arithmetic, but for RigidBody::setRotation's renormalisation (the last bit).
    for (int c = 0; c < 4; ++c)
        EXPECT_NEAR(b.getOrientation()[c], alone.orientation[c], 1e-14);
    EXPECT_NEAR(glm::length(b.getAngularMomentum() - alone.momentum), 0.0, 1e-14);
}

TEST(RigidWorld, KineticEnergyCountsTheSpin)
{
    World world = roomWorld(0.0);
    RigidBody& b = addRigid(world, Shape::sphere(0.5), 100.0, dvec3(0.0, 2.0, 0.0));
    b.setAngularVelocity(dvec3(0.0, 3.0, 0.0));
    const double inertia = 0.4 * b.getMass() * 0.25;
    EXPECT_NEAR(world.kineticEnergy(0), 0.5 * inertia * 9.0, 1e-12);
}

TEST(RigidWorld, ARigidBodyOnATwoBodySpringIsRefusedByName)
{
    World world = roomWorld();
    addRigid(world, Shape::box(dvec3(0.2)), 500.0, dvec3(0.0, 1.0, 0.0)).setName("crate");
    Particle p;
    p.setPos(dvec3(0.0, 2.0, 0.0));
    world.addParticle(p);
    world.addForce(std::make_unique<TwoBodySpring>(0, 1, 10.0, 1.0, 0.0));
    try {
        world.step(0.01);
        FAIL() << "no error";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("'crate'"), std::string::npos) << e.what();
    }
}

namespace {

/// The blow dryer's wrench on one rigid body at rest at its current pose.
Wrench dryerWrench(const RigidBody& body, const BlowDryerField& field)
{
    std::vector<ClonePtr<Body>> bodies;
    bodies.emplace_back(body.clone());
    const std::vector<State> states{body.getState()};
    const std::vector<Pose> poses{Pose{body.getOrientation(), body.getAngularVelocity()}};
    std::vector<dvec3> forces(1, dvec3(0.0)), torques(1, dvec3(0.0));
    Accumulators out{forces, torques};
    BlowDryer(field).accumulate(BodyStates{bodies, states, {}, {}, poses}, out);
    return {forces[0], torques[0]};
}

BlowDryerField testJet()
{
    return {.height = 3.0, .nozzleRadius = 0.2, .topRadius = 1.2, .strength = 50.0,
            .direction = FlowDirection::ConeFlow};
}

} // namespace

// The dryer acts over the surface: a ball centred on the jet's axis feels no torque, one off the
// axis does, and a small body feels what a particle at its centre would.
TEST(RigidWorld, DryerOverTheSurfaceTurnsOnlyWhatIsOffTheAxis)
{
    const BlowDryerField jet = testJet();
    RigidBody ball(Shape::sphere(0.2), 100.0);
    ball.setOrientation(glm::angleAxis(0.7, glm::normalize(dvec3(1.0, 2.0, 3.0))));
    ball.setPos(dvec3(0.0, 1.0, 0.0));
    const Wrench onAxis = dryerWrench(ball, jet);
    EXPECT_GT(onAxis.force.y, 1.0);
    EXPECT_LT(glm::length(onAxis.torque), 1e-12 * glm::length(onAxis.force));
    ball.setPos(dvec3(0.35, 1.0, 0.0));
    EXPECT_GT(glm::length(dryerWrench(ball, jet).torque), 1e-3 * glm::length(onAxis.force) * 0.2);
    RigidBody box(Shape::box(dvec3(0.3, 0.1, 0.2)), 100.0);
    box.setPos(dvec3(0.4, 1.0, 0.1));
    EXPECT_GT(glm::length(dryerWrench(box, jet).torque), 1e-3);
    RigidBody speck(Shape::box(dvec3(1e-4)), 100.0);
    speck.setPos(dvec3(0.3, 1.2, -0.1));
    const dvec3 point = blowDryerForce(jet, speck.getPos());
    EXPECT_LT(glm::length(dryerWrench(speck, jet).force - point), 1e-3 * glm::length(point));
}

// Tied by a corner to an anchored spring, a box swings and twists; with no damping its energy
// (kinetic with the spin, gravity's and the spring's) stays constant to RK4's accuracy.
TEST(RigidWorld, BoxOnASpringAtACornerSwingsTwistsAndKeepsItsEnergy)
{
    World world = roomWorld();
    RigidBody& box = addRigid(world, Shape::box(dvec3(0.3, 0.2, 0.1)), 300.0, dvec3(0.4, 2.5, 0.2));
    box.setIntegrator(Integrator::RK4);
    world.addForce(std::make_unique<Spring>(0, dvec3(0.0, 3.5, 0.0), 200.0, 0.6, 0.0, dvec3(0.15, 0.1, 0.05)));
    const double e0 = world.totalEnergy();
    double worst = 0.0, spin = 0.0;
    for (int n = 0; n < 3000; ++n) {
        world.step(0.001);
        worst = std::max(worst, std::abs(world.totalEnergy() / e0 - 1.0));
        spin = std::max(spin, glm::length(box.getAngularVelocity()));
    }
    EXPECT_LT(worst, 1e-6);
    EXPECT_GT(spin, 1.0); // it twists
}

// Angular drag -k omega on a ball spinning in zero gravity: omega(t) = omega0 exp(-k t / I).
TEST(RigidWorld, AngularDragSlowsASpinExponentially)
{
    World world = roomWorld(0.0);
    RigidBody& ball = addRigid(world, Shape::sphere(0.3), 500.0, dvec3(0.0, 2.0, 0.0));
    ball.setIntegrator(Integrator::RK4);
    ball.setAngularVelocity(dvec3(0.0, 5.0, 1.0));
    const double k = 0.4, inertia = ball.getInertiaBody()[0][0];
    world.addForce(std::make_unique<Drag>(0.0, k));
    for (int n = 0; n < 1000; ++n)
        world.step(0.001);
    const dvec3 expected = dvec3(0.0, 5.0, 1.0) * std::exp(-k * world.time() / inertia);
    EXPECT_LT(glm::length(ball.getAngularVelocity() - expected), 1e-9 * glm::length(expected));
}

// The dice bench's pile, stepped through its throw and landing on 1 and on 2 threads: the same
// states to the bit (each body's step and contacts are its own arithmetic).
TEST(RigidWorld, ManyDiceStepTheSameOnAnyNumberOfThreads)
{
    Scene one = manyDice(1000), two = manyDice(1000);
    one.world.setThreads(1);
    two.world.setThreads(2);
    for (int n = 0; n < 200; ++n) {
        one.world.step(one.dt);
        two.world.step(two.dt);
    }
    for (std::size_t i = 0; i < one.world.bodyCount(); ++i) {
        const auto& a = static_cast<const RigidBody&>(one.world.body(i));
        const auto& b = static_cast<const RigidBody&>(two.world.body(i));
        ASSERT_EQ(a.getPos(), b.getPos()) << i;
        ASSERT_EQ(a.getVel(), b.getVel()) << i;
        ASSERT_EQ(a.getOrientation(), b.getOrientation()) << i;
        ASSERT_EQ(a.getAngularMomentum(), b.getAngularMomentum()) << i;
        ASSERT_EQ(one.world.bounceCount(i), two.world.bounceCount(i)) << i;
    }
}

// A huge island (a block of 16 x 16 x 16 boxes, some 12,000 contacts, its top layers thrown down
// into it): its collision and velocity passes go half by half, the two halves' contacts on two
// cores at once (halves.hpp). The same states to the bit on 1 and on 2 threads.
TEST(RigidWorld, AHugeIslandStepsTheSameOnAnyNumberOfThreads)
{
    World worlds[2] = {roomWorld(), roomWorld()};
    for (int w = 0; w < 2; ++w) {
        worlds[w].setThreads(w + 1);
        for (int i = 0; i < 16; ++i)
            for (int j = 0; j < 16; ++j)
                for (int k = 0; k < 16; ++k) {
                    RigidBody& box = addRigid(worlds[w], Shape::box(dvec3(0.1)), 600.0,
                                              dvec3(-0.8 + 0.1005 * i, 0.05 + 0.1005 * k, -0.8 + 0.1005 * j));
                    if (k >= 12)
                        box.setVel(dvec3(0.0, -1.0 - 0.1 * (i % 3), 0.0));
                }
    }
    for (int n = 0; n < 3; ++n)
        for (World& world : worlds)
            world.step(0.005);
    for (std::size_t i = 0; i < worlds[0].bodyCount(); ++i) {
        const auto& a = static_cast<const RigidBody&>(worlds[0].body(i));
        const auto& b = static_cast<const RigidBody&>(worlds[1].body(i));
        ASSERT_EQ(a.getPos(), b.getPos()) << i;
        ASSERT_EQ(a.getVel(), b.getVel()) << i;
        ASSERT_EQ(a.getAngularMomentum(), b.getAngularMomentum()) << i;
    }
}

// A contact that bounces starts from no impulse, whatever the body's memory of the last step
// holds (warm starting a bounce would feed its restitution with the last step's push). With
// restitution 0 a bouncing contact's target speed, -e times its arriving speed, is +0, and a
// resting one's at a gap of zero or less is -0: equal as numbers, so only a flag tells them
// apart. A ball arriving at 2 m/s a tenth of a millimetre into the floor, with a remembered
// impulse at that very point, ends its step bit for bit as one with no memory does.
TEST(RigidContact, ABouncingContactIsNotWarmStartedEvenWithRestitutionZero)
{
    // A ball arriving at 2 m/s a tenth of a millimetre into the floor (B, static): one contact
    // point, with and without a remembered impulse.
    const double dt = 0.001, mass = 33.5;
    rigid::SolverBody ball;
    ball.position = dvec3(0.0, 0.2 - 1e-4, 0.0);
    ball.inverseMass = 1.0 / mass;
    ball.inverseInertia = dmat3(1.0 / (0.4 * mass * 0.04));
    ball.vStart = dvec3(0.3, -2.0, 0.1);
    ball.v = ball.vFree = ball.vStart + dvec3(0.0, -kG * dt, 0.0);
    ball.endPosition = ball.position + ball.v * dt;
    const rigid::SolverBody floor;
    auto solve = [&](double remembered) {
        std::vector<rigid::SolverBody> bodies{ball, floor};
        std::vector<rigid::Contact> contacts(1);
        rigid::Contact& c = contacts[0];
        c.a = 0;
        c.b = 1;
        c.friction = 0.5;
        c.restitution = 0.0;
        c.radiusA = 0.2;
        c.count = 1;
        c.points[0].normal = dvec3(0.0, -1.0, 0.0);
        c.points[0].point = dvec3(0.0, -1e-4, 0.0);
        c.points[0].anchorB = dvec3(0.0);
        c.points[0].separation = -1e-4;
        c.points[0].normalImpulse = remembered;
        c.points[0].tangentImpulse[0] = remembered / 5.0;
        rigid::SolverSettings settings;
        settings.dt = dt;
        settings.restingSpeed = 2.0 * kG * dt;
        const std::uint32_t island[] = {0};
        rigid::ContactSolver solver;
        const std::uint32_t moving[] = {0};
        solver.prepare(contacts, island, moving, bodies, settings);
        EXPECT_TRUE(solver.collide());
        solver.warmStart();
        for (int k = 0; k < 10; ++k)
            solver.solveVelocities();
        return bodies[0];
    };
    const rigid::SolverBody withMemory = solve(5.0), without = solve(0.0);
    EXPECT_EQ(withMemory.v, without.v);
    EXPECT_EQ(withMemory.shift, without.shift);
    EXPECT_EQ(withMemory.w, without.w);
    EXPECT_NEAR(withMemory.v.y, 0.0, 1e-12); // e = 0: it stops against the floor
}
