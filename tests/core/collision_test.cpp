// Collisions against exact oracles: the analytic bouncing trajectory (apex h, bounce
// period 2 sqrt(2h/g)), the apex sequence e^(2k) h, resting contact, and the guarantee
// that nothing ever ends a step outside the room.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <random>
#include <vector>

#include "core/surfaces/room_surfaces.hpp"
#include "core/surfaces/surface_tests.hpp"
#include "pba/forces.hpp"
#include "pba/scene/scene.hpp"
#include "pba/world.hpp"

using namespace pba;

namespace {

constexpr double kG = 9.81;

World dropWorld(Integrator integrator, CollisionResponse response, double h, double restitution = 1.0)
{
    World world;
    world.addForce(std::make_unique<Gravity>(dvec3(0, -kG, 0)));
    world.setGround(0.0);
    world.setCollisionResponse(response);
    Particle p;
    p.setPos(dvec3(0, h, 0));
    p.setIntegrator(integrator);
    p.setCor(restitution);
    world.addParticle(p);
    return world;
}

/// Height and vertical velocity of a ball dropped from rest at h with e = 1.
/// With t0 = sqrt(2h/g) the motion repeats every 2 t0; s is the time since the last apex.
std::pair<double, double> exactBounce(double h, double t)
{
    const double t0 = std::sqrt(2 * h / kG);
    const double s = std::fmod(t + t0, 2 * t0) - t0;
    return {h - 0.5 * kG * s * s, -kG * s};
}

std::vector<double> apexHeights(World& world, double dt, double duration)
{
    std::vector<double> apexes;
    double previousVy = world.body(0).getVel().y;
    for (int n = 0; n < static_cast<int>(duration / dt); ++n) {
        const double y = world.body(0).getPos().y;
        world.step(dt);
        const double vy = world.body(0).getVel().y;
        if (previousVy > 0 && vy <= 0)
            apexes.push_back(std::max(y, world.body(0).getPos().y));
        previousVy = vy;
    }
    return apexes;
}

} // namespace

TEST(Collisions, ResponseNamesRoundTrip)
{
    for (CollisionResponse response : kAllCollisionResponses)
        EXPECT_EQ(collisionResponseFromName(collisionResponseName(response)), response);
    EXPECT_FALSE(collisionResponseFromName("bounce").has_value());
}

// Velocity Verlet and RK4 are exact for constant acceleration and the exact response adds
// no error of its own, so they follow the analytic bouncing path to rounding at any dt.
TEST(Collisions, ExactResponseReproducesTheAnalyticBounceAtAnyDt)
{
    const double h = 2.0;
    for (Integrator integrator : {Integrator::VelocityVerlet, Integrator::RK4}) {
        for (double dt : {0.0005, 0.01, 0.05, 0.1}) {
            World world = dropWorld(integrator, CollisionResponse::Exact, h);
            const int steps = static_cast<int>(std::lround(10.0 / dt));
            for (int n = 1; n <= steps; ++n) {
                world.step(dt);
                const auto [y, vy] = exactBounce(h, n * dt);
                ASSERT_NEAR(world.body(0).getPos().y, y, 1e-9) << integratorName(integrator) << " dt " << dt << " n " << n;
                ASSERT_NEAR(world.body(0).getVel().y, vy, 1e-8) << integratorName(integrator) << " dt " << dt;
            }
            // 10 s holds floor(10 / period + 1/2) impacts: the period is 2 sqrt(2h/g).
            const double period = 2 * std::sqrt(2 * h / kG);
            EXPECT_EQ(world.bounceCount(0), static_cast<std::uint64_t>(std::floor(10.0 / period + 0.5)));
        }
    }
}

// Forward Euler in free fall gains exactly g^2 dt^2 / 2 per unit mass each step (x += v dt,
// v -= g dt: the potential falls by g v dt, the kinetic rises by g v dt + g^2 dt^2 / 2), so
// before the first impact the energy is E0 + n m g^2 dt^2 / 2 after n steps, and after ten
// seconds of bounces it is above the start in every response.
TEST(Collisions, ForwardEulerGainsEnergyInEveryResponse)
{
    for (CollisionResponse response : kAllCollisionResponses) {
        for (double dt : {0.001, 0.01, 0.05}) {
            World world = dropWorld(Integrator::ForwardEuler, response, 2.0);
            const double e0 = world.energy(0), m = world.body(0).getMass();
            const int steps = static_cast<int>(10.0 / dt);
            int n = 0;
            for (; n < steps && world.bounceCount(0) == 0; ++n) {
                world.step(dt);
                if (world.bounceCount(0) == 0) {
                    ASSERT_NEAR(world.energy(0), e0 + (n + 1) * m * kG * kG * dt * dt / 2, 1e-10 * e0)
                        << collisionResponseName(response) << " dt " << dt << " step " << n + 1;
                }
            }
            ASSERT_GT(n, 10) << "the first fall takes more than a few steps";
            for (; n < steps; ++n)
                world.step(dt);
            EXPECT_GT(world.energy(0), e0) << collisionResponseName(response) << " dt " << dt;
        }
    }
}

// The practical's classic result: with the mirror response semi-implicit Euler keeps its
// bounce: its energy oscillates within the shadow-energy band (about g |v| dt / 2 per unit
// mass mid-flight) but neither grows nor decays over many bounces.
TEST(Collisions, SemiImplicitEulerKeepsItsEnergyInReflectMode)
{
    for (double dt : {0.0005, 0.001, 0.005, 0.01, 0.02, 0.05}) {
        World world = dropWorld(Integrator::SemiImplicitEuler, CollisionResponse::Reflect, 2.0);
        const double e0 = world.energy(0);
        double sum = 0.0;
        const int steps = static_cast<int>(std::lround(10.0 / dt));
        for (int n = 0; n < steps; ++n) {
            world.step(dt);
            sum += world.energy(0) / e0;
        }
        // The band is widest at the largest dt (g |v| dt / 2 grows with dt): these bounds are its width there.
        EXPECT_NEAR(sum / steps, 1.0, 0.05) << "time-averaged energy, dt " << dt;
        EXPECT_NEAR(world.energy(0) / e0, 1.0, 0.06) << "final energy, dt " << dt;
    }
}

TEST(Collisions, RestitutionGivesApexESquaredToTheKTimesTheDropHeight)
{
    const double h = 2.0;
    for (double e : {0.9, 0.7}) {
        World world = dropWorld(Integrator::RK4, CollisionResponse::Exact, h, e);
        const std::vector<double> apexes = apexHeights(world, 0.001, 6.0);
        ASSERT_GE(apexes.size(), 4u);
        for (std::size_t k = 0; k < 4; ++k) {
            // Sampled apexes lie within g dt^2 / 2 of the true one.
            EXPECT_NEAR(apexes[k], std::pow(e, 2.0 * double(k + 1)) * h, 1e-5) << "e " << e << " bounce " << k + 1;
        }
    }
}

TEST(Collisions, ABodyAtRestOnTheGroundNeitherSinksNorBouncesForever)
{
    for (Integrator integrator : kAllIntegrators) {
        World world = dropWorld(integrator, CollisionResponse::Exact, 1.0, 0.5);
        for (int n = 0; n < 2000; ++n) {
            world.step(0.01);
            ASSERT_GE(world.body(0).getPos().y, 0.0);
        }
        const auto bounces = world.bounceCount(0);
        for (int n = 0; n < 500; ++n)
            world.step(0.01);
        EXPECT_EQ(world.body(0).getPos().y, 0.0) << integratorName(integrator);
        EXPECT_EQ(world.body(0).getVel().y, 0.0) << integratorName(integrator);
        EXPECT_EQ(world.bounceCount(0), bounces) << integratorName(integrator);
    }
}

TEST(Collisions, BallStartingOnTheGroundWithRestitutionOneStaysThere)
{
    World world = dropWorld(Integrator::SemiImplicitEuler, CollisionResponse::Exact, 0.0, 1.0);
    for (int n = 0; n < 100; ++n)
        world.step(0.01);
    EXPECT_EQ(world.body(0).getPos().y, 0.0);
    EXPECT_EQ(world.body(0).getVel().y, 0.0);
}

// An apex above the ceiling inside one step: the exact response finds the impact even
// though the step starts and ends inside the room. Velocity Verlet follows constant
// acceleration exactly, so the step ends where the analytic path does: up to the ceiling at
// y = 1 at t* (0.9 + 2 t - g t^2 / 2 = 1), the vertical velocity reversed there (restitution 1),
// then falling for the rest of the step.
TEST(Collisions, ExactResponseCatchesAnImpactInsideAStep)
{
    World world;
    world.addForce(std::make_unique<Gravity>(dvec3(0, -kG, 0)));
    world.setRoom({dvec3(-1, 0, -1), dvec3(1, 1, 1)});
    Particle p;
    p.setPos(dvec3(0, 0.9, 0));
    p.setVel(dvec3(0, 2.0, 0)); // would rise to 0.9 + 4 / (2 g) = 1.104
    p.setIntegrator(Integrator::VelocityVerlet);
    world.addParticle(p);
    const double dt = 0.1;
    world.step(dt); // without the ceiling y(0.1) = 1.0509, which lies inside the room
    const double impact = (2.0 - std::sqrt(4.0 - 2.0 * kG * 0.1)) / kG;
    const double up = 2.0 - kG * impact, after = dt - impact;
    EXPECT_EQ(world.bounceCount(0), 1u);
    EXPECT_NEAR(world.body(0).getPos().y, 1.0 - up * after - 0.5 * kG * after * after, 1e-12);
    EXPECT_NEAR(world.body(0).getVel().y, -up - kG * after, 1e-12);
    EXPECT_EQ(world.body(0).getPos().x, 0.0);
    EXPECT_EQ(world.body(0).getVel().x, 0.0);
}

// The oracle for the fold: the reflect rule as the practical states it, mirror across the wall
// the body is beyond until it is beyond none, one wall at a time with no limit on the passes.
// The fold must end in the same place with the same velocity and the same number of bounces,
// for bodies up to 40 slab widths out, moving either way or not at all, with any restitution.
TEST(Collisions, FoldingIntoASlabIsMirroringBetweenItsWallsUntilInside)
{
    const Plane low{dvec3(1, 0, 0), -2.0};   // x >= -2
    const Plane high{dvec3(-1, 0, 0), -3.0}; // x <= 3
    std::array<SlabT<double>, 3> slabs;
    const std::array<Plane, 2> walls{low, high};
    ASSERT_EQ(boxSlabs(std::span<const Plane>(walls), slabs), 1);
    const SlabT<double> slab = slabs[0];
    EXPECT_EQ(slab.axis, 0);
    EXPECT_EQ(slab.lo, -2.0);
    EXPECT_EQ(slab.hi, 3.0);
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> where(-200.0, 200.0), speed(-50.0, 50.0);
    for (double e : {1.0, 0.8, 0.0}) {
        for (int trial = 0; trial < 2000; ++trial) {
            const dvec3 start(0.5, 1, 1);
            const double from = where(rng);
            dvec3 x(from, 1, 1), v(trial % 5 == 0 ? 0.0 : speed(rng), 0, 0);
            dvec3 mx = x, mv = v;
            int expected = 0;
            for (bool mirrored = true; mirrored;) {
                const bool offLow = mirrorBack(low, e, start, mx, mv, expected); // both walls every round
                const bool offHigh = mirrorBack(high, e, start, mx, mv, expected);
                mirrored = offLow || offHigh;
            }
            const int bounces = foldIntoSlab(slab, e, x.x, v.x);
            ASSERT_NEAR(x.x, mx.x, 1e-11) << "from " << from << " e " << e;
            ASSERT_NEAR(v.x, mv.x, 1e-12 * (1 + std::abs(mv.x))) << "from " << from << " e " << e;
            ASSERT_EQ(bounces, expected) << "from " << from << " e " << e;
        }
    }
}

// The shaft's wall in a pass of the rule: a body in the shaft beyond its radius is put just
// inside it with its outward radial velocity reflected with restitution and its tangential and
// vertical velocity kept (a Particle and a swarm's vectorised pass both get this from
// mirrorBack); a body in the shaft within the radius, or one above the floor, is left bit for
// bit as it was.
TEST(Collisions, TheShaftWallIsPartOfTheFloorsPass)
{
    const Plane floor{dvec3(0, 1, 0), 0.0, 0.25, dvec3(0.0)};
    const double e = 0.6;
    const dvec3 start(0.2, -0.02, 0.0); // already in the shaft
    dvec3 x(0.3, -0.03, 0.1), v(2.0, -0.5, 1.0);
    int bounces = 0;
    EXPECT_TRUE(mirrorBack(floor, e, start, x, v, bounces));
    EXPECT_EQ(bounces, 1);
    const dvec3 out = glm::normalize(dvec3(0.3, 0.0, 0.1));
    EXPECT_LT(std::hypot(x.x, x.z), 0.25);
    EXPECT_NEAR(std::hypot(x.x, x.z), 0.25, 1e-14);
    EXPECT_EQ(x.y, -0.03);
    const dvec3 v0(2.0, -0.5, 1.0);
    EXPECT_NEAR(glm::dot(v, out), -e * glm::dot(v0, out), 1e-14);
    EXPECT_NEAR(glm::length(v - glm::dot(v, out) * out), glm::length(v0 - glm::dot(v0, out) * out), 1e-14);
    const std::array<std::pair<dvec3, dvec3>, 2> leftAlone{std::pair{start, dvec3(0.1, -0.03, -0.2)},  // within
                                                           std::pair{dvec3(1, 1, 1), dvec3(1, 0.5, 1)}}; // above
    for (const auto& [from, at] : leftAlone) {
        dvec3 y = at, w(2.0, -0.5, 1.0);
        int none = 0;
        EXPECT_FALSE(mirrorBack(floor, e, from, y, w, none));
        EXPECT_EQ(none, 0);
        EXPECT_EQ(y, at);
        EXPECT_EQ(w, dvec3(2.0, -0.5, 1.0));
    }
}

// A wall's geometry with its axis known when compiled (AxisPlaneT, what a swarm's passes use)
// gives the rule what the generic plane gives: for each axis and side, with a hole, for bodies
// beyond the plane, over the hole, in the shaft, at the shaft's wall and clear of it. Without
// fused multiply-adds both do the same roundings, bit for bit. With them, where the compiler
// fuses a product into a sum is its choice for each form (the release build fuses both alike,
// and a swarm's results do not change; a sanitizer build does not): the same to the last bits.
template <class T>
void expectAxisPlanesAgree(bool exact)
{
    const auto same = [exact](const Vec3<T>& a, const Vec3<T>& b) {
        if (exact)
            return a == b;
        const T ulps = T(8) * std::numeric_limits<T>::epsilon();
        return glm::all(glm::lessThanEqual(glm::abs(a - b), ulps * (T(1) + glm::abs(a))));
    };
    std::mt19937 rng(11);
    std::uniform_real_distribution<T> near(T(-0.6), T(0.6)), speed(T(-3), T(3));
    for (int axis = 0; axis < 3; ++axis) {
        for (T sign : {T(1), T(-1)}) {
            Vec3<T> normal(T(0)), centre(T(0.1), T(-0.2), T(0.15));
            normal[axis] = sign;
            const PlaneT<T> plane{normal, T(0.3) * sign, T(0.25), centre};
            int cases = 0;
            for (int trial = 0; trial < 4000; ++trial) {
                const Vec3<T> start(near(rng), near(rng), near(rng)), at(near(rng), near(rng), near(rng));
                const Vec3<T> velocity(speed(rng), speed(rng), speed(rng));
                for (bool mirror : {true, false}) {
                    Vec3<T> x = at, v = velocity, ax = at, av = velocity;
                    int bounces = 0, axisBounces = 0;
                    const auto rule = [&](const auto& p, Vec3<T>& y, Vec3<T>& w, int& b) {
                        return mirror ? mirrorBack(p, T(0.6), start, y, w, b) : snapBack(p, T(0.6), start, y, w, b);
                    };
                    const bool moved = rule(plane, x, v, bounces);
                    const bool axisMoved =
                        withPlaneGeometry(plane, [&](const auto& p) { return rule(p, ax, av, axisBounces); });
                    cases += moved;
                    ASSERT_EQ(moved, axisMoved) << "axis " << axis << " trial " << trial;
                    ASSERT_TRUE(same(x, ax)) << "axis " << axis << " trial " << trial;
                    ASSERT_TRUE(same(v, av)) << "axis " << axis << " trial " << trial;
                    ASSERT_EQ(bounces, axisBounces) << "axis " << axis << " trial " << trial;
                }
            }
            EXPECT_GT(cases, 1000); // the rule had work in many of the trials
        }
    }
}

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
// Again compiled with fused multiply-adds, as a swarm's loops are on a CPU that has them.
[[gnu::target("arch=x86-64-v3"), gnu::flatten]] void expectAxisPlanesAgreeWithFma()
{
    expectAxisPlanesAgree<float>(false);
    expectAxisPlanesAgree<double>(false);
}
#endif

TEST(Collisions, AnAxisPlaneGivesWhatThePlaneGives)
{
#if defined(__FMA__)
    constexpr bool kExact = false; // a build for a CPU with fused multiply-adds (-march=native)
#else
    constexpr bool kExact = true;
#endif
    expectAxisPlanesAgree<float>(kExact);
    expectAxisPlanesAgree<double>(kExact);
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
    if (__builtin_cpu_supports("fma") && __builtin_cpu_supports("avx2"))
        expectAxisPlanesAgreeWithFma();
#endif
}

// A body inside the slab is left exactly as it was (bit for bit), and one beyond 2^22 widths or
// not finite is left to the last line of defence.
TEST(Collisions, FoldingLeavesBodiesInsideAndHopelessOnesAlone)
{
    const SlabT<float> slab{1, 0.0f, 4.0f};
    for (float c : {0.0f, 1e-30f, 2.5f, 4.0f}) {
        float x = c, v = -3.0f;
        EXPECT_EQ(foldIntoSlab(slab, 1.0f, x, v), 0);
        EXPECT_EQ(x, c);
        EXPECT_EQ(v, -3.0f);
    }
    for (float c : {1e30f, -1e30f, std::numeric_limits<float>::infinity(), std::nanf("")}) {
        float x = c, v = 1.0f;
        EXPECT_EQ(foldIntoSlab(slab, 1.0f, x, v), 0);
        EXPECT_EQ(v, 1.0f);
    }
}

// The swarm's one-loop surface test for a box agrees with the plane-by-plane one it replaces:
// the same points are clear (the margins agree to rounding), the same counts are beyond each
// wall, the same depths, and the floor's hole does not stop the floor from being one of the
// box's walls.
// The grille below a floor's hole faces +y as the floor does: the box is the floor's, the inner
// wall, so a point clear of the box is clear of the grille too. The slabs, which leave out walls
// with a hole, take the grille.
TEST(Collisions, TheBoxTakesTheInnerOfTwoWallsOnASide)
{
    std::vector<PlaneT<float>> planes{
        {Vec3<float>(0, 1, 0), 0.0f, 0.3f, Vec3<float>(0.0f)}, {Vec3<float>(0, -1, 0), -4.0f},
        {Vec3<float>(1, 0, 0), -2.0f}, {Vec3<float>(-1, 0, 0), -2.0f},
        {Vec3<float>(0, 0, 1), -2.0f}, {Vec3<float>(0, 0, -1), -2.0f},
        {Vec3<float>(0, 1, 0), -0.05f}};
    const auto box = boxWalls(std::span<const PlaneT<float>>(planes));
    ASSERT_TRUE(box.has_value());
    EXPECT_EQ(box->plane[2], 0);
    EXPECT_EQ(box->lo[1], 0.0f);
    std::array<SlabT<float>, 3> slabs;
    ASSERT_EQ(boxSlabs(std::span<const PlaneT<float>>(planes), slabs), 3);
    EXPECT_EQ(slabs[1].lo, -0.05f);
}

TEST(Collisions, TheBoxSurfaceTestAgreesWithThePlaneByPlaneOne)
{
    std::vector<PlaneT<float>> planes{
        {Vec3<float>(0, 1, 0), 0.0f, 0.3f, Vec3<float>(0.0f)}, {Vec3<float>(0, -1, 0), -4.0f},
        {Vec3<float>(1, 0, 0), -2.0f}, {Vec3<float>(-1, 0, 0), -2.0f},
        {Vec3<float>(0, 0, 1), -2.0f}, {Vec3<float>(0, 0, -1), -2.0f}};
    const auto box = boxWalls(std::span<const PlaneT<float>>(planes));
    ASSERT_TRUE(box.has_value());
    EXPECT_EQ(box->mask, 0b111111u);
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> coordinate(-2.5f, 4.5f);
    constexpr std::size_t n = 4096;
    std::vector<float> x(n), y(n), z(n), boxMargin(n), planeMargin(n, std::numeric_limits<float>::infinity());
    for (std::size_t k = 0; k < n; ++k) {
        x[k] = coordinate(rng), y[k] = coordinate(rng), z[k] = coordinate(rng);
        if (k % 7 == 0)
            x[k] = 2.0f; // on a wall
        if (k % 11 == 0)
            y[k] = 1e-7f; // within the floor's contact tolerance
    }
    setClearanceInBox(*box, x.data(), y.data(), z.data(), n, boxMargin.data());
    for (std::size_t w = 0; w < 6; ++w)
        lowerClearance(planes[std::size_t(box->plane[w])], x.data(), y.data(), z.data(), n, planeMargin.data());
    std::vector<std::uint8_t> unclear(n);
    const std::uint32_t unclearCount =
        markUnclearInBox(ClearRegionT<float>(*box), x.data(), y.data(), z.data(), n, unclear.data());
    std::uint32_t notPositive = 0;
    for (std::size_t k = 0; k < n; ++k) {
        ASSERT_EQ(boxMargin[k] > 0.0f, planeMargin[k] > 0.0f) << "point " << k;
        ASSERT_NEAR(boxMargin[k], planeMargin[k], 1e-6f) << "point " << k;
        ASSERT_EQ(unclear[k] == 1, !(boxMargin[k] > 0.0f)) << "point " << k; // the test without margins
        notPositive += unclear[k];
    }
    EXPECT_EQ(unclearCount, notPositive);
}

TEST(Collisions, NothingEverEndsAStepOutsideTheRoom)
{
    std::mt19937 rng(42);
    std::uniform_real_distribution<double> speed(-500.0, 500.0);
    const Aabb room{dvec3(-2, 0, -2), dvec3(2, 4, 2)};
    for (CollisionResponse response : kAllCollisionResponses) {
        for (Integrator integrator : kAllIntegrators) {
            World world;
            world.addForce(std::make_unique<Gravity>(dvec3(0, -kG, 0)));
            world.setRoom(room);
            world.setCollisionResponse(response);
            for (int i = 0; i < 10; ++i) {
                Particle p;
                p.setPos(dvec3(0, 2, 0));
                p.setVel(dvec3(speed(rng), speed(rng), speed(rng)));
                p.setIntegrator(integrator);
                p.setCor(i % 2 ? 1.0 : 0.8);
                world.addParticle(p);
            }
            for (int n = 0; n < 300; ++n) {
                world.step(0.1);
                for (std::size_t i = 0; i < world.bodyCount(); ++i) {
                    const dvec3 x = world.body(i).getPos();
                    ASSERT_TRUE(x.x >= room.min.x && x.x <= room.max.x && x.y >= room.min.y && x.y <= room.max.y &&
                                x.z >= room.min.z && x.z <= room.max.z)
                        << collisionResponseName(response) << " " << integratorName(integrator) << " step " << n;
                }
            }
        }
    }
}

TEST(World, NonFiniteStateStopsTheStepAndNamesTheBody)
{
    World world;
    Particle p;
    p.setName("bob");
    p.setIntegrator(Integrator::ForwardEuler);
    p.setPos(dvec3(0, 1, 0));
    world.addParticle(p);
    world.addForce(std::make_unique<Spring>(0, dvec3(0.0), 1e300, 0.0, 0.0));
    world.step(1.0);
    try {
        for (int n = 0; n < 10; ++n)
            world.step(1.0);
        FAIL() << "no error";
    } catch (const NonFiniteStateError& e) {
        EXPECT_EQ(e.body(), "bob");
        EXPECT_NE(std::string(e.what()).find("smaller dt"), std::string::npos);
        EXPECT_TRUE(std::isfinite(world.body(0).getPos().y)); // rolled back to the last finite state
        EXPECT_EQ(world.stepCount() + 1, e.step());
    }
}

TEST(World, CopiesAreDeepAndInterpolationBlendsStates)
{
    World a = loadScene("integrators").world;
    World b = a;
    a.step(0.01);
    EXPECT_EQ(b.stepCount(), 0u);
    EXPECT_EQ(b.body(1).getPos().y, 2.0);
    const State mid = a.interpolatedState(1, 0.5);
    EXPECT_DOUBLE_EQ(mid.pos.y, 0.5 * (a.previousState(1).pos.y + a.body(1).getPos().y));
}

// The declared one-body step of pba/collision.hpp (for a program that steps its own point
// against planes) is the World's rule: a ball dropped from rest with velocity Verlet and the
// exact response, 50 steps of 0.01 s before it lands at t = sqrt(4 / g) = 0.64 s, is where
// x = h - g t^2 / 2 puts it (velocity Verlet is exact for constant acceleration), and it equals
// the World's ball bit for bit.
TEST(Collision, TheDeclaredOneBodyStepIsTheWorldsRule)
{
    const std::array<Plane, 1> ground = groundPlanes(0.0);
    dvec3 x(0, 2, 0), v(0.0);
    const std::function<dvec3(const dvec3&, const dvec3&)> gravity = [](const dvec3&, const dvec3&) {
        return dvec3(0, -kG, 0);
    };
    World world = dropWorld(Integrator::VelocityVerlet, CollisionResponse::Exact, 2.0);
    int bounces = 0;
    for (int i = 0; i < 50; ++i) {
        bounces += stepWithCollisions(CollisionResponse::Exact, Integrator::VelocityVerlet,
                                      std::span<const Plane>(ground), 1.0, x, v, 0.01, gravity);
        world.step(0.01);
    }
    EXPECT_EQ(bounces, 0);
    EXPECT_NEAR(x.y, 2.0 - 0.5 * kG * 0.25, 1e-12);
    EXPECT_EQ(x, world.body(0).getPos());
    EXPECT_EQ(v, world.body(0).getVel());
}

namespace {

/// A World's surfaces in float: the blow-dryer scenes' room, the hole in its floor and the
/// grille at the bottom of the hole's shaft (or a ground, with or without the hole).
std::vector<PlaneT<float>> worldSurfaces(bool room, bool hole)
{
    std::vector<PlaneT<float>> planes;
    if (room) {
        const auto walls = roomPlanes(Vec3<float>(-2, 0, -2), Vec3<float>(2, 4, 2));
        planes.assign(walls.begin(), walls.end());
    } else {
        planes.push_back(groundPlanes(0.0f)[0]);
    }
    if (hole) {
        planes[0].holeRadius = 0.25f;
        planes[0].holeCentre = Vec3<float>(0.3f, 0.0f, -0.2f);
        planes.push_back({Vec3<float>(0, 1, 0), -0.1f});
    }
    return planes;
}

} // namespace

// The swarm's form of a World's surfaces is found for the four a World makes (a ground or a
// room, with the dryer's hole and grille or without) and for nothing else.
TEST(Collisions, RoomSurfacesAreFoundForAWorldsPlanesOnly)
{
    for (bool room : {false, true})
        for (bool hole : {false, true}) {
            const auto planes = worldSurfaces(room, hole);
            const auto surfaces = roomSurfaces(std::span<const PlaneT<float>>(planes));
            ASSERT_TRUE(surfaces.has_value()) << room << hole;
            EXPECT_EQ(surfaces->hasHole(), hole);
        }
    auto angled = worldSurfaces(true, false);
    angled.push_back({glm::normalize(Vec3<float>(-1, 0, -1)), -2.0f});
    auto swapped = worldSurfaces(true, false);
    std::swap(swapped[2], swapped[3]);
    auto grilleWithoutHole = worldSurfaces(true, false);
    grilleWithoutHole.push_back({Vec3<float>(0, 1, 0), -0.1f});
    auto holeInAWall = worldSurfaces(true, false);
    holeInAWall[2].holeRadius = 0.1f;
    for (const auto& planes : {angled, swapped, grilleWithoutHole, holeInAWall})
        EXPECT_FALSE(roomSurfaces(std::span<const PlaneT<float>>(planes)).has_value());
}

// The swarm's collision pass over the floor, its hole and the grille, for a body it says it has
// finished, gives what a Particle's whole reflect or clamp rule gives, bit for bit: bodies
// thrown at every surface of the room, over the hole, in the shaft and at its wall, from
// starts above the floor and in the shaft. The rest, at a wall, the ceiling or the shaft's wall,
// it hands to that rule.
TEST(Collisions, TheSwarmsFloorPassIsAParticlesRuleWhereItFinishes)
{
    std::mt19937 rng(17);
    std::uniform_real_distribution<float> across(-2.3f, 2.3f), height(-0.15f, 4.2f), nearFloor(-0.15f, 0.05f),
        speed(-6.0f, 6.0f), unit(0.0f, 1.0f);
    for (bool room : {false, true})
        for (bool hole : {false, true}) {
            const auto planes = worldSurfaces(room, hole);
            const std::span<const PlaneT<float>> span(planes);
            const RoomSurfacesT<float> surfaces = *roomSurfaces(span);
            for (CollisionResponse response : {CollisionResponse::Reflect, CollisionResponse::Clamp}) {
                int finished = 0, handedOn = 0;
                for (int trial = 0; trial < 20000; ++trial) {
                    // Half near the floor and the hole, where a landed swarm is.
                    const bool low = trial % 2 == 0;
                    const float r = 0.3f * unit(rng), angle = 6.2832f * unit(rng);
                    Vec3<float> x = low ? Vec3<float>(0.3f + r * std::cos(angle), nearFloor(rng), -0.2f + r * std::sin(angle))
                                        : Vec3<float>(across(rng), height(rng), across(rng));
                    const Vec3<float> v(speed(rng), speed(rng), speed(rng));
                    const Vec3<float> start = x - 0.002f * v + Vec3<float>(0.0f, trial % 3 == 0 ? -0.02f : 0.0f, 0.0f);
                    Vec3<float> passedX = x, passedV = v;
                    int bounces = 0;
                    const float back = response == CollisionResponse::Reflect ? 2.0f : 1.0f;
                    if (hole)
                        surfaces.commonPass<true>(0.6f, back, start, passedX, passedV, bounces);
                    else
                        surfaces.commonPass<false>(0.6f, back, start, passedX, passedV, bounces);
                    if (surfaces.needsWholeRule(passedX)) {
                        ++handedOn;
                        continue;
                    }
                    ++finished;
                    Vec3<float> ruleV = v;
                    const int ruleBounces = response == CollisionResponse::Reflect
                                                ? reflectAfterStep(span, 0.6f, start, x, ruleV)
                                                : clampAfterStep(span, 0.6f, start, x, ruleV);
                    ASSERT_EQ(passedX, x) << collisionResponseName(response) << " trial " << trial;
                    ASSERT_EQ(passedV, ruleV) << collisionResponseName(response) << " trial " << trial;
                    ASSERT_EQ(bounces, ruleBounces) << collisionResponseName(response) << " trial " << trial;
                }
                EXPECT_GT(finished, 10000) << room << hole; // most bodies, the rest handed on
                if (room || hole) { // a ground alone leaves nothing to the whole rule
                    EXPECT_GT(handedOn, 100) << room << hole;
                }
            }
        }
}
