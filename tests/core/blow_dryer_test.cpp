// The blow dryer's field against its definition, and its dynamics against the harmonic
// oscillator it becomes on the axis.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <numbers>
#include <random>
#include <vector>

#include "pba/blow_dryer.hpp"
#include "pba/detail/blow_dryer_kernel.hpp"
#include "pba/forces.hpp"
#include "pba/integrator.hpp"
#include "pba/scene/scene.hpp"
#include "pba/world.hpp"

using namespace pba;

namespace {

BlowDryerField dryer(FlowDirection direction, Falloff axial = Falloff::Linear, Falloff radial = Falloff::Linear)
{
    BlowDryerField f;
    f.nozzle = dvec3(0.0);
    f.height = 3.0;
    f.nozzleRadius = 0.2;
    f.topRadius = 1.2;
    f.strength = 30.0;
    f.axialFalloff = axial;
    f.radialFalloff = radial;
    f.direction = direction;
    return f;
}

double radiusAt(const BlowDryerField& f, double h) { return f.nozzleRadius + (f.topRadius - f.nozzleRadius) * h / f.height; }

constexpr std::array<Falloff, 3> kFalloffs{Falloff::Linear, Falloff::Quadratic, Falloff::Smooth};
constexpr std::array<FlowDirection, 2> kDirections{FlowDirection::Vertical, FlowDirection::ConeFlow};

} // namespace

TEST(BlowDryerField, FalloffProfilesAtTheirQuarterPoints)
{
    // linear u, quadratic u^2, smooth u^2 (3 - 2u)
    EXPECT_DOUBLE_EQ(falloff(Falloff::Linear, 0.25), 0.25);
    EXPECT_DOUBLE_EQ(falloff(Falloff::Linear, 0.75), 0.75);
    EXPECT_DOUBLE_EQ(falloff(Falloff::Quadratic, 0.25), 0.0625);
    EXPECT_DOUBLE_EQ(falloff(Falloff::Quadratic, 0.5), 0.25);
    EXPECT_DOUBLE_EQ(falloff(Falloff::Quadratic, 0.75), 0.5625);
    EXPECT_DOUBLE_EQ(falloff(Falloff::Smooth, 0.25), 0.15625);
    EXPECT_DOUBLE_EQ(falloff(Falloff::Smooth, 0.5), 0.5);
    EXPECT_DOUBLE_EQ(falloff(Falloff::Smooth, 0.75), 0.84375);
    for (Falloff kind : kFalloffs) {
        EXPECT_EQ(falloff(kind, 0.0), 0.0);
        EXPECT_EQ(falloff(kind, 1.0), 1.0);
    }
}

// The kernel compiled for an upward axis (what a swarm step uses in every built-in scene) is
// the general kernel with the axis known: the same force, in float, to a few roundings, at
// points inside, on the rim of and outside the cone, for every falloff and direction.
TEST(BlowDryerField, TheUpwardKernelIsTheGeneralOneWithTheAxisKnown)
{
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> across(-1.5f, 1.5f), along(-0.5f, 3.5f);
    for (FlowDirection direction : kDirections) {
        for (Falloff axial : kFalloffs) {
            for (Falloff radial : kFalloffs) {
                BlowDryerField field = dryer(direction, axial, radial);
                field.nozzle = dvec3(0.3, 0.0, -0.2);
                const BlowDryerKernelT<float> f(field.as<float>());
                for (int k = 0; k < 2000; ++k) {
                    const Vec3<float> x(across(rng), along(rng), across(rng));
                    const Vec3<float> general = blowDryerForce<DryerAxis::Any>(f, x);
                    const Vec3<float> up = blowDryerForce<DryerAxis::Up>(f, x);
                    ASSERT_LE(glm::length(up - general), 1e-5f * field.strength)
                        << "at " << x.x << " " << x.y << " " << x.z;
                }
            }
        }
    }
}

namespace {

// Whether two vectors are the same bits (signed zeros apart, unlike ==).
bool sameBits(const Vec3<float>& a, const Vec3<float>& b)
{
    return std::memcmp(&a, &b, sizeof a) == 0;
}

// Accelerations a swarm's loop adds the dryer's force to: gravity (its zeros made +0, as the
// swarm's loop makes them) and drag at a few velocities, never -0.
std::vector<Vec3<float>> accelerationsBesideTheDryer(std::mt19937& rng)
{
    std::uniform_real_distribution<float> signedUnit(-1.0f, 1.0f);
    std::vector<Vec3<float>> out;
    for (const Vec3<float> gravity : {Vec3<float>(0.0f, -9.81f, 0.0f), Vec3<float>(-0.0f, -9.81f, -0.0f),
                                      Vec3<float>(1.5f, -9.0f, -0.25f)}) {
        const Vec3<float> g = gravity + Vec3<float>(0.0f);
        out.push_back(g);
        const Vec3<float> v(signedUnit(rng), signedUnit(rng), 0.0f);
        out.push_back(g + dragForce(0.4f, v));
        out.push_back(g + dragForce(0.5f, 2.0f * g)); // gravity cancelled: +0 + -0 and g - g are +0
    }
    return out;
}

} // namespace

// Where blowDryerMayPush says the dryer cannot push, blowDryerForce is a zero vector, so a
// swarm steps a particle there with the acceleration without the dryer and a zero that depends
// on x (0 x, which a compiler cannot take out of the loop): gravity and drag plus the force,
// and plus 0 x, are the same bits, upward or tilted, with a shaft or without. Wherever the
// force is not zero, blowDryerMayPush says it may push (points near the cone's side and the
// shaft's wall included, where the squared test's margin matters).
TEST(BlowDryerField, AwayFromTheConeAndShaftTheAccelerationIsAsWithoutTheDryer)
{
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> across(-1.6f, 1.6f), along(-0.6f, 3.6f), unit(0.0f, 1.0f);
    const std::vector<Vec3<float>> beside = accelerationsBesideTheDryer(rng);
    for (const bool tilted : {false, true}) {
        for (const bool shaft : {false, true}) {
            BlowDryerField field = dryer(FlowDirection::ConeFlow, Falloff::Linear, Falloff::Smooth);
            field.shaft = shaft;
            if (tilted)
                field.axis = glm::normalize(dvec3(0.2, 1.0, -0.1));
            const BlowDryerKernelT<float> f(field.as<float>());
            std::size_t away = 0, negativeZeros = 0; // the force's -0 components: what makes bits differ
            for (int k = 0; k < 200000; ++k) {
                Vec3<float> x(across(rng), along(rng), across(rng));
                if (k % 2 == 0 && !tilted) { // on the cone's side or the shaft's wall, to a few roundings
                    const float h = along(rng), angle = 6.2831853f * unit(rng);
                    const float radius = h >= 0.0f ? float(field.nozzleRadius) + float(field.topRadius - field.nozzleRadius) * h / float(field.height)
                                                   : float(field.nozzleRadius);
                    x = Vec3<float>(radius * std::cos(angle), h, radius * std::sin(angle));
                }
                const Vec3<float> whole = tilted ? blowDryerForce<DryerAxis::Any>(f, x) : blowDryerForce<DryerAxis::Up>(f, x);
                const bool may = tilted ? blowDryerMayPush<DryerAxis::Any>(f, x) : blowDryerMayPush<DryerAxis::Up>(f, x);
                if (may)
                    continue;
                ++away;
                ASSERT_EQ(whole, Vec3<float>(0.0f)) << "at " << x.x << " " << x.y << " " << x.z;
                for (int c = 0; c < 3; ++c)
                    negativeZeros += std::signbit(whole[c]) ? 1u : 0u;
                for (const Vec3<float>& a : beside)
                    ASSERT_TRUE(sameBits(a + whole, a + 0.0f * x)) << "at " << x.x << " " << x.y << " " << x.z;
            }
            EXPECT_GT(away, 50000u) << "tilted " << tilted << " shaft " << shaft;
            EXPECT_GT(negativeZeros, 10000u) << "tilted " << tilted << " shaft " << shaft;
        }
    }
}

// Far above and below the nozzle (where h^2 overflows a float) the force is still a zero
// vector, and the acceleration beside it the same bits with 0 x.
TEST(BlowDryerField, FarFromTheNozzleTheAccelerationIsStillAsWithoutTheDryer)
{
    std::mt19937 rng(12);
    const std::vector<Vec3<float>> beside = accelerationsBesideTheDryer(rng);
    for (const bool tilted : {false, true}) {
        BlowDryerField field = dryer(FlowDirection::ConeFlow, Falloff::Linear, Falloff::Smooth);
        if (tilted)
            field.axis = glm::normalize(dvec3(0.2, 1.0, -0.1));
        const BlowDryerKernelT<float> f(field.as<float>());
        for (const float y : {3e19f, -3e19f, -2.0f, 1e30f}) {
            const Vec3<float> x(0.5f, y, 0.3f);
            const Vec3<float> whole = tilted ? blowDryerForce<DryerAxis::Any>(f, x) : blowDryerForce<DryerAxis::Up>(f, x);
            ASSERT_EQ(whole, Vec3<float>(0.0f)) << "tilted " << tilted << " y " << y;
            for (const Vec3<float>& a : beside)
                ASSERT_TRUE(sameBits(a + whole, a + 0.0f * x)) << "tilted " << tilted << " y " << y;
        }
    }
}

// blowDryerMayPushWithin against what it replaces: blowDryerMayPush at every point velocity
// Verlet and RK4 evaluate the acceleration at, with the acceleration away from the dryer
// (gravity, drag and 0 x). Wherever some point may be pushed, the one test at the
// start says so: starts on and near the cone's side, top and rim and the shaft's wall, at
// speeds from rest to 60 m/s, for every dt from the practical's range and beyond, with and
// without drag, upward or tilted, widening or narrowing, at the origin or far from it.
TEST(BlowDryerField, OneTestAtTheStartCoversEveryPointAStepEvaluates)
{
    std::mt19937 rng(24);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f), signedUnit(-1.0f, 1.0f);
    std::size_t reached = 0; // starts that are not pushed but a later point is
    for (int variant = 0; variant < 8; ++variant) {
        const bool tilted = variant & 1, shaft = variant & 2, elsewhere = variant & 4;
        BlowDryerField field = dryer(FlowDirection::ConeFlow, Falloff::Linear, Falloff::Smooth);
        field.shaft = shaft;
        if (tilted)
            field.axis = glm::normalize(dvec3(0.2, 1.0, -0.1));
        if (elsewhere) { // a narrowing cone far from the origin
            field.nozzle = dvec3(37.0, -4.0, 81.0);
            field.topRadius = 0.05;
        }
        const BlowDryerKernelT<float> f(field.as<float>());
        const Vec3<float> axis(field.axis), nozzle(field.nozzle);
        const Vec3<float> side = glm::normalize(glm::cross(axis, Vec3<float>(1.0f, 0.0f, 0.0f)));
        const Vec3<float> other = glm::cross(axis, side);
        const auto may = [&](const Vec3<float>& x) {
            return tilted ? blowDryerMayPush<DryerAxis::Any>(f, x) : blowDryerMayPush<DryerAxis::Up>(f, x);
        };
        const auto random3 = [&] { return Vec3<float>(signedUnit(rng), signedUnit(rng), signedUnit(rng)); };
        for (int k = 0; k < 100000; ++k) {
            // A point on the cone's side, top or rim, or the shaft's wall, and a step from near it.
            const float h = float(field.height) * (1.2f * unit(rng) - 0.1f), angle = 6.2831853f * unit(rng);
            const bool wall = shaft && k % 3 == 0;
            const double clamped = std::clamp(double(h), 0.0, field.height);
            const float radius = float(wall ? field.nozzleRadius : radiusAt(field, clamped));
            const Vec3<float> around = std::cos(angle) * side + std::sin(angle) * other;
            const Vec3<float> across(radius * std::cos(angle), -std::abs(h), radius * std::sin(angle));
            const Vec3<float> onSurface = wall ? nozzle + across : nozzle + h * axis + radius * around;
            const float speed = k % 5 == 0 ? 0.0f : 60.0f * std::pow(unit(rng), 3.0f);
            const Vec3<float> v = speed * glm::normalize(random3() + 1e-3f);
            const float dt = 0.0005f * std::pow(400.0f, unit(rng)); // 0.0005 to 0.2
            const float drag = k % 2 == 0 ? 0.0f : 4.0f * unit(rng);
            const Vec3<float> gravity = k % 4 == 0 ? Vec3<float>(0.0f, -9.81f, 0.0f) : 30.0f * unit(rng) * random3();
            const Vec3<float> x = onSurface + (1.5f * (speed * dt + 60.0f * dt * dt) + 1e-4f) * random3();
            const BlowDryerReach reach(f, dt, glm::length(dvec3(gravity)), drag);
            const bool within = tilted ? blowDryerMayPushWithin<DryerAxis::Any>(reach, x, v)
                                       : blowDryerMayPushWithin<DryerAxis::Up>(reach, x, v);
            for (const Integrator integrator : {Integrator::VelocityVerlet, Integrator::RK4}) {
                bool pushed = false;
                Vec3<float> y = x, u = v;
                integrate(integrator, y, u, dt, [&](const Vec3<float>& at, const Vec3<float>& velocity) {
                    pushed = pushed || may(at);
                    return gravity + dragForce(drag, velocity) + 0.0f * at;
                });
                reached += pushed && !may(x);
                ASSERT_TRUE(!pushed || within) << "variant " << variant << " integrator " << integratorName(integrator)
                                               << " x " << x.x << " " << x.y << " " << x.z << " v " << v.x << " "
                                               << v.y << " " << v.z << " dt " << dt << " drag " << drag;
            }
        }
    }
    EXPECT_GT(reached, 10000u);
}

// At rest, the reach is the dryer's slack and a step's fall: a particle resting 2% of the radius
// outside the cone or the shaft's wall is away from the dryer, one on them is not.
TEST(BlowDryerField, AtRestTheReachIsAHairAroundTheConeAndShaft)
{
    BlowDryerField field = dryer(FlowDirection::ConeFlow);
    field.shaft = true;
    const BlowDryerKernelT<float> f(field.as<float>());
    const BlowDryerReach reach(f, 0.002, 9.81, 0.0);
    const Vec3<float> rest(0.0f);
    for (const double h : {0.0, 0.5, 1.5, 2.9}) {
        const float edge = float(radiusAt(field, h));
        EXPECT_TRUE(blowDryerMayPushWithin<DryerAxis::Up>(reach, Vec3<float>(edge, float(h), 0.0f), rest)) << h;
        EXPECT_FALSE(blowDryerMayPushWithin<DryerAxis::Up>(reach, Vec3<float>(1.02f * edge, float(h), 0.0f), rest))
            << h;
    }
    const float wall = float(field.nozzleRadius);
    EXPECT_TRUE(blowDryerMayPushWithin<DryerAxis::Up>(reach, Vec3<float>(0.0f, -0.5f, 0.99f * wall), rest));
    EXPECT_FALSE(blowDryerMayPushWithin<DryerAxis::Up>(reach, Vec3<float>(0.0f, -0.5f, 1.02f * wall), rest));
    const float above = 1.02f * float(field.height) + 0.01f;
    EXPECT_FALSE(blowDryerMayPushWithin<DryerAxis::Up>(reach, Vec3<float>(0.0f, above, 0.0f), rest));
    // No bound on the step (drag times dt at least 1): every particle may be pushed.
    const BlowDryerReach unbounded(f, 0.5, 9.81, 2.0);
    EXPECT_TRUE(blowDryerMayPushWithin<DryerAxis::Up>(unbounded, Vec3<float>(50.0f, 20.0f, -30.0f), rest));
}

TEST(BlowDryerField, MaximalAtTheNozzleOnTheAxisAndZeroAtTopEdgeAndOutside)
{
    for (FlowDirection direction : kDirections) {
        for (Falloff axial : kFalloffs) {
            for (Falloff radial : kFalloffs) {
                const BlowDryerField f = dryer(direction, axial, radial);
                EXPECT_NEAR(glm::length(blowDryerForce(f, dvec3(0.0))), f.strength, 1e-12);
                EXPECT_EQ(blowDryerForce(f, dvec3(0, 3.0, 0)), dvec3(0.0));     // the top
                EXPECT_EQ(blowDryerForce(f, dvec3(0, 3.5, 0)), dvec3(0.0));     // above
                EXPECT_EQ(blowDryerForce(f, dvec3(0, -0.01, 0)), dvec3(0.0));   // below the nozzle
                for (double h : {0.0, 0.7, 1.5, 2.9}) {
                    const double edge = radiusAt(f, h);
                    EXPECT_EQ(blowDryerForce(f, dvec3(edge, h, 0)), dvec3(0.0)) << "on the edge at h " << h;
                    EXPECT_EQ(blowDryerForce(f, dvec3(0, h, edge * 1.01)), dvec3(0.0)) << "outside at h " << h;
                }
            }
        }
    }
}

TEST(BlowDryerField, NeverIncreasesUpwardsOrOutwards)
{
    for (FlowDirection direction : kDirections) {
        for (Falloff profile : kFalloffs) {
            const BlowDryerField f = dryer(direction, profile, profile);
            double previous = INFINITY;
            for (double h = 0.0; h <= 3.2; h += 0.01) {
                const double m = glm::length(blowDryerForce(f, dvec3(0, h, 0)));
                EXPECT_LE(m, previous + 1e-12) << "along the axis at h " << h;
                previous = m;
            }
            for (double h : {0.0, 1.0, 2.5}) {
                previous = INFINITY;
                for (double r = 0.0; r <= 1.5; r += 0.005) {
                    const double m = glm::length(blowDryerForce(f, dvec3(r * 0.6, h, r * 0.8)));
                    EXPECT_LE(m, previous + 1e-12) << "outwards at h " << h << " r " << r;
                    previous = m;
                }
            }
        }
    }
}

TEST(BlowDryerField, PointsAlongTheAxisOnTheAxisInBothModes)
{
    for (FlowDirection direction : kDirections) {
        BlowDryerField f = dryer(direction);
        f.axis = glm::normalize(dvec3(1, 2, 0.5));
        for (double h : {0.0, 1.0, 2.0, 2.9}) {
            const dvec3 force = blowDryerForce(f, h * f.axis);
            EXPECT_NEAR(glm::length(glm::cross(force, f.axis)), 0.0, 1e-12);
            EXPECT_GT(glm::dot(force, f.axis), 0.0);
        }
    }
}

// In cone-flow mode the direction just inside the edge is the cone's side direction
// (from (r0, 0) to (R, H) in the axis-radius plane), and it varies continuously.
TEST(BlowDryerField, ConeFlowIsParallelToTheSideAtTheEdgeAndContinuous)
{
    const BlowDryerField f = dryer(FlowDirection::ConeFlow);
    const dvec3 radial = glm::normalize(dvec3(1, 0, 1));
    const dvec3 side = glm::normalize(f.height * f.axis + (f.topRadius - f.nozzleRadius) * radial);
    for (double h : {0.1, 1.0, 2.0, 2.8}) {
        const dvec3 x = h * f.axis + 0.9999 * radiusAt(f, h) * radial;
        const dvec3 direction = glm::normalize(blowDryerForce(f, x));
        EXPECT_NEAR(glm::length(glm::cross(direction, side)), 0.0, 1e-3) << "h " << h;
        EXPECT_GT(glm::dot(direction, f.axis), 0.0); // away from the nozzle
    }
    // Continuity: neighbouring samples differ by at most a Lipschitz bound times the spacing.
    const double step = 1e-3;
    for (double h = 0.0; h < 3.0; h += 0.05) {
        for (double r = 0.0; r < 1.3; r += 0.01) {
            const dvec3 a = blowDryerForce(f, dvec3(r, h, 0));
            const dvec3 b = blowDryerForce(f, dvec3(r + step, h, 0));
            const dvec3 c = blowDryerForce(f, dvec3(r, h + step, 0));
            EXPECT_LT(glm::length(a - b), 0.2) << "r " << r << " h " << h;
            EXPECT_LT(glm::length(a - c), 0.2) << "r " << r << " h " << h;
        }
    }
}

// On the axis, with a linear axial falloff and a vertical direction, the net force is
// S (1 - h/H) - m g: a spring of stiffness S/H about h* = H (1 - m g / S). Released at rest,
// the particle oscillates about h* with period 2 pi sqrt(m H / S).
TEST(BlowDryerDynamics, OnTheAxisItIsAHarmonicOscillator)
{
    const double g = 9.81, m = 1.0;
    const BlowDryerField f = dryer(FlowDirection::Vertical);
    World world;
    world.addForce(std::make_unique<Gravity>(dvec3(0, -g, 0)));
    world.addForce(std::make_unique<BlowDryer>(f));
    Particle p;
    p.setPos(dvec3(0, 1.5, 0));
    p.setIntegrator(Integrator::RK4);
    world.addParticle(p);
    const double hStar = f.height * (1 - m * g / f.strength);
    const double period = 2 * std::numbers::pi * std::sqrt(m * f.height / f.strength);
    const double dt = 1e-3;
    const int perPeriod = static_cast<int>(std::lround(period / dt));
    double sum = 0.0;
    std::vector<double> upCrossings;
    double previous = world.body(0).getPos().y;
    for (int n = 0; n < 5 * perPeriod; ++n) {
        world.step(dt);
        const double y = world.body(0).getPos().y;
        sum += y;
        if (previous < hStar && y >= hStar) // linear interpolation of the crossing time
            upCrossings.push_back((n + (hStar - previous) / (y - previous)) * dt);
        previous = y;
    }
    EXPECT_NEAR(sum / (5 * perPeriod), hStar, 2e-3 * hStar);
    ASSERT_GE(upCrossings.size(), 4u);
    EXPECT_NEAR((upCrossings.back() - upCrossings.front()) / double(upCrossings.size() - 1), period, 1e-6);
}

TEST(BlowDryerDynamics, TheBallNeverLeavesTheRoomInASimulatedHour)
{
    Scene scene = loadScene("blow-dryer");
    World& world = scene.world;
    const Aabb room = *world.room();
    const double grille = room.min.y - world.floorHole()->depth;
    const auto steps = static_cast<int>(3600.0 / scene.dt);
    for (int n = 0; n < steps; ++n) {
        world.step(scene.dt);
        const dvec3 x = world.body(0).getPos();
        ASSERT_TRUE(x.x >= room.min.x && x.x <= room.max.x && x.z >= room.min.z && x.z <= room.max.z &&
                    x.y <= room.max.y && x.y >= grille)
            << "step " << n << " at (" << x.x << ", " << x.y << ", " << x.z << ")";
        if (x.y < room.min.y) { // below the floor only inside the hole's shaft
            ASSERT_LE(std::hypot(x.x, x.z), world.floorHole()->radius) << "step " << n;
        }
    }
}

// The floor has a hole of the nozzle's radius: with the dryer off, a ball dropped over it
// falls through to the grille and stays in the shaft; one dropped beside it bounces on the floor.
TEST(FloorHole, ABallOverTheHoleLandsOnTheGrilleInEveryResponse)
{
    for (CollisionResponse response : kAllCollisionResponses) {
        for (Integrator integrator : kAllIntegrators) {
            World world;
            world.addForce(std::make_unique<Gravity>(dvec3(0, -9.81, 0)));
            world.setRoom({dvec3(-2, 0, -2), dvec3(2, 4, 2)});
            world.setFloorHole({dvec3(0.0), 0.2, 0.05});
            world.setCollisionResponse(response);
            Particle over, beside;
            over.setPos(dvec3(0.05, 1, 0));
            over.setVel(dvec3(0.3, 0, 0)); // drifts sideways into the shaft's wall
            over.setCor(0.0); // no rebound: it must stay in the shaft
            beside.setPos(dvec3(1, 1, 0));
            beside.setCor(0.5);
            over.setIntegrator(integrator);
            beside.setIntegrator(integrator);
            world.addParticle(over);
            world.addParticle(beside);
            for (int n = 0; n < 1000; ++n) {
                world.step(0.01);
                const dvec3 a = world.body(0).getPos();
                ASSERT_GE(a.y, -0.05 - 1e-12) << collisionResponseName(response);
                if (a.y < 0.0) {
                    ASSERT_LE(std::hypot(a.x, a.z), 0.2 + 1e-12) << collisionResponseName(response) << " n " << n;
                }
                ASSERT_GE(world.body(1).getPos().y, 0.0);
            }
            EXPECT_LT(world.body(0).getPos().y, 0.0) << collisionResponseName(response) << " "
                                                      << integratorName(integrator);
            EXPECT_NEAR(world.body(1).getPos().y, 0.0, 0.01);
        }
    }
}

// ---- The shaft: air leaves the dryer at the grille ----

// A dryer in the floor pushes in the hole's shaft with the nozzle's force, the same across the
// shaft (plug flow), along the axis; beside the hole and without a hole, nothing below the nozzle.
TEST(BlowDryerShaft, PushesWithTheNozzlesForceAcrossTheShaftOnly)
{
    for (FlowDirection direction : kDirections) {
        BlowDryerField f = dryer(direction, Falloff::Linear, Falloff::Smooth);
        EXPECT_EQ(blowDryerForce(f, dvec3(0, -0.02, 0)), dvec3(0.0)) << "no hole: the seed's field";
        f.shaft = true;
        for (const dvec3& x : {dvec3(0, -0.02, 0), dvec3(0.19, -0.04, 0), dvec3(0.1, -1e-9, -0.15), dvec3(0, -0.05, 0)})
            EXPECT_EQ(blowDryerForce(f, x), dvec3(0, f.strength, 0)) << x.x << " " << x.y << " " << x.z;
        EXPECT_EQ(blowDryerForce(f, dvec3(0.21, -0.02, 0)), dvec3(0.0)) << "under the floor beside the hole";
        EXPECT_EQ(blowDryerForce(f, dvec3(0.0, 1.0, 0)), blowDryerForce(dryer(direction, Falloff::Linear, Falloff::Smooth),
                                                                          dvec3(0.0, 1.0, 0)))
            << "above the nozzle the field is the seed's";
    }
}

// The built-in scene's dryer is in the floor: `pba field` shows the shaft's push.
TEST(BlowDryerShaft, TheSceneLoaderPutsTheShaftUnderAFloorNozzle)
{
    const Scene scene = loadScene("blow-dryer");
    const auto* dryer = dynamic_cast<const BlowDryer*>(&scene.world.force(scene.world.forceCount() - 1));
    ASSERT_NE(dryer, nullptr);
    EXPECT_TRUE(dryer->field().shaft);
    EXPECT_EQ(blowDryerForce(dryer->field(), dvec3(0, -0.02, 0)), dvec3(0, dryer->field().strength, 0));
}

namespace {

/// The room with the blow-dryer scene's hole and a seed-model dryer (no air terms) of `strength`,
/// and one ball dropped slowly into the hole.
World ballDroppedIntoTheHole(double strength, CollisionResponse response, Integrator integrator)
{
    World world;
    world.addForce(std::make_unique<Gravity>(dvec3(0, -9.81, 0)));
    world.setRoom({dvec3(-2, 0, -2), dvec3(2, 4, 2)});
    world.setFloorHole({dvec3(0.0), 0.2, 0.05});
    world.setCollisionResponse(response);
    BlowDryerField f = dryer(FlowDirection::Vertical, Falloff::Linear, Falloff::Smooth);
    f.strength = strength;
    f.shaft = true;
    world.addForce(std::make_unique<BlowDryer>(f));
    Particle ball;
    ball.setPos(dvec3(0.12, -0.001, -0.08)); // just inside the hole, falling slowly
    ball.setVel(dvec3(0.05, -0.3, 0.0));
    ball.setCor(0.5);
    ball.setIntegrator(integrator);
    world.addParticle(ball);
    return world;
}

} // namespace

// Stronger than its weight, the dryer blows a ball that falls into its hole out again within a
// fraction of a second; weaker, the ball lies on the grille, kept in the shaft.
TEST(BlowDryerShaft, ABallDroppedSlowlyIntoTheHoleIsBlownOutWhenTheDryerCanLiftIt)
{
    for (CollisionResponse response : kAllCollisionResponses) {
        for (Integrator integrator : kAllIntegrators) {
            const std::string label = std::string(collisionResponseName(response)) + " " +
                                      std::string(integratorName(integrator));
            World strong = ballDroppedIntoTheHole(30.0, response, integrator);
            double outAt = -1.0;
            for (int n = 0; n < 200 && outAt < 0.0; ++n) {
                strong.step(0.005);
                if (strong.body(0).getPos().y > 0.0)
                    outAt = strong.time();
            }
            EXPECT_GT(outAt, 0.0) << label;
            EXPECT_LT(outAt, 0.5) << label;

            World weak = ballDroppedIntoTheHole(5.0, response, integrator);
            for (int n = 0; n < 400; ++n)
                weak.step(0.005);
            EXPECT_NEAR(weak.body(0).getPos().y, -0.05, 1e-3) << label;
        }
    }
}

// ---- The air terms ----

// With neither air key the force is the seed's, to the bit, whatever the velocity: the air
// terms add exact zeros.
TEST(BlowDryerAir, WithoutTheAirKeysTheForceIsTheSeedsWhateverTheVelocity)
{
    std::mt19937 random(5);
    std::uniform_real_distribution<double> across(-1.5, 1.5), up(-0.1, 3.6), speed(-20, 20);
    for (FlowDirection direction : kDirections)
        for (Falloff radial : kFalloffs) {
            BlowDryerField f = dryer(direction, Falloff::Linear, radial);
            f.shaft = true;
            const BlowDryerKernelT<double> kernel(f);
            for (int k = 0; k < 2000; ++k) {
                const dvec3 x(across(random), up(random), across(random));
                const dvec3 v(speed(random), speed(random), speed(random));
                EXPECT_EQ(blowDryerForce(f, x, v), (blowDryerForce<DryerAxis::Any, false>(kernel, x)));
            }
        }
}

// In the shaft the air is uniform: u = U along the axis. A ball there under gravity and the air
// drag c (u - v), c = S / U, obeys m v' = S - m g - c v: released at rest it reaches the
// terminal velocity v_T = (S - m g) / c as v(t) = v_T (1 - exp(-t / tau)), tau = m / c.
TEST(BlowDryerAir, ABallInUniformAirReachesItsTerminalVelocityWithTimeConstantMOverC)
{
    const double g = 9.81, m = 2.0, S = 30.0, U = 6.0, c = S / U, tau = m / c, vT = (S - m * g) / c;
    for (Integrator integrator : kAllIntegrators) {
        BlowDryerField f = dryer(FlowDirection::Vertical);
        f.nozzle = dvec3(0, 100, 0); // a deep shaft below it: uniform air all the way
        f.nozzleRadius = 1.0;
        f.topRadius = 2.0;
        f.strength = S;
        f.shaft = true;
        f.airSpeed = U;
        World world;
        world.addForce(std::make_unique<Gravity>(dvec3(0, -g, 0)));
        world.addForce(std::make_unique<BlowDryer>(f));
        Particle ball;
        ball.setMass(m);
        ball.setIntegrator(integrator);
        world.addParticle(ball);
        const double dt = 1e-3;
        double worst = 0.0;
        for (int n = 1; n <= 4000; ++n) {
            world.step(dt);
            const double t = n * dt;
            worst = std::max(worst, std::abs(world.body(0).getVel().y - vT * (1.0 - std::exp(-t / tau))));
            if (n == static_cast<int>(std::lround(tau / dt))) {
                EXPECT_NEAR(world.body(0).getVel().y / vT, 1.0 - std::exp(-1.0), 1e-3) << integratorName(integrator);
            }
        }
        // First-order methods err by O(dt) relative to v_T / tau; RK4 by rounding.
        EXPECT_LT(worst, integrator == Integrator::RK4 ? 1e-9 : 2e-3 * vT) << integratorName(integrator);
        EXPECT_NEAR(world.body(0).getVel().y, vT, 1e-3 * vT) << integratorName(integrator);
        EXPECT_NEAR(world.body(0).getVel().x, 0.0, 1e-12);
    }
}

// The pull is (beta / 2) times the gradient of |u|^2 across the axis. Linear falloffs give a
// closed form: w = (1 - s)(1 - r/R(h)), so beta U^2 w dw/dr = -beta U^2 (1 - s)^2 (1 - r/R) / R.
// For every profile it matches a central difference of |u|^2 from the air's velocity.
TEST(BlowDryerAir, ThePullIsHalfBetaTimesTheGradientOfTheAirSpeedSquaredAcrossTheAxis)
{
    BlowDryerField f = dryer(FlowDirection::Vertical);
    f.airSpeed = 12.0;
    f.axisPull = 0.7;
    for (const double h : {0.3, 1.0, 2.2})
        for (const double r : {0.05, 0.3, 0.6}) {
            const double R = radiusAt(f, h), s = h / f.height;
            if (r >= R)
                continue;
            const dvec3 x(r * 0.6, h, r * 0.8);
            const dvec3 F = blowDryerForce(f, x); // at rest: the push (vertical) and the pull
            const double expected = -f.axisPull * f.airSpeed * f.airSpeed * (1 - s) * (1 - s) * (1 - r / R) / R;
            EXPECT_NEAR(F.x, expected * 0.6, 1e-12) << h << " " << r;
            EXPECT_NEAR(F.z, expected * 0.8, 1e-12) << h << " " << r;
        }
    for (FlowDirection direction : kDirections)
        for (Falloff axial : kFalloffs)
            for (Falloff radial : kFalloffs) {
                BlowDryerField g = dryer(direction, axial, radial);
                g.airSpeed = 12.0;
                g.axisPull = 0.7;
                for (const double h : {0.4, 1.5, 2.5})
                    for (const double r : {0.1, 0.35, 0.7}) {
                        if (r >= radiusAt(g, h) - 1e-3)
                            continue;
                        const dvec3 dir(0.8, 0.0, -0.6);
                        auto speed2 = [&](double rr) {
                            const dvec3 u = blowDryerAirVelocity(g, dvec3(0, h, 0) + rr * dir);
                            return glm::dot(u, u);
                        };
                        const double e = 1e-6;
                        const double gradient = (speed2(r + e) - speed2(r - e)) / (2 * e);
                        BlowDryerField pushOnly = g;
                        pushOnly.axisPull = 0.0;
                        const dvec3 x = dvec3(0, h, 0) + r * dir;
                        const double pull = glm::dot(blowDryerForce(g, x) - blowDryerForce(pushOnly, x), dir);
                        EXPECT_NEAR(pull, 0.5 * g.axisPull * gradient, 1e-5 * (1 + std::abs(pull)))
                            << falloffName(axial) << " " << falloffName(radial) << " h " << h << " r " << r;
                    }
            }
}

// A ball off the axis at its hover height, with the air terms, is pulled back and settles on
// the axis; without them (the seed's vertical field) nothing pushes it back, and any sideways
// speed carries it out of the cone.
TEST(BlowDryerAir, TheAirTermsHoldABallInTheJetThatTheSeedsFieldLoses)
{
    for (const bool air : {false, true}) {
        BlowDryerField f = dryer(FlowDirection::Vertical, Falloff::Linear, Falloff::Smooth);
        if (air) {
            f.airSpeed = 15.0;
            f.axisPull = 1.0;
        }
        World world;
        world.addForce(std::make_unique<Gravity>(dvec3(0, -9.81, 0)));
        world.addForce(std::make_unique<BlowDryer>(f));
        Particle ball;
        ball.setPos(dvec3(0.3, f.height * (1 - 9.81 / f.strength), 0));
        ball.setVel(dvec3(0.4, 0.0, 0.2));
        world.addParticle(ball);
        for (int n = 0; n < 4000; ++n)
            world.step(0.005);
        const dvec3 x = world.body(0).getPos();
        if (air) {
            EXPECT_LT(std::hypot(x.x, x.z), 0.02);
            EXPECT_TRUE(insideBlowDryerCone(f, x));
        } else {
            EXPECT_FALSE(insideBlowDryerCone(f, x));
        }
    }
}

// Leaving out the pull's arithmetic (kPull false) for a kernel without a pull changes nothing:
// the same force to the bit, inside the cone, in the shaft and outside.
TEST(BlowDryerField, WithoutAPullTheShortKernelGivesTheSameForce)
{
    BlowDryerField field;
    field.strength = 3.0;
    field.height = 2.0;
    field.nozzleRadius = 0.2;
    field.topRadius = 1.0;
    field.direction = FlowDirection::ConeFlow;
    field.airSpeed = 10.0;
    field.shaft = true;
    const BlowDryerKernelT<double> kernel(field);
    ASSERT_EQ(kernel.pull, 0.0);
    for (const dvec3 x : {dvec3(0.1, 0.5, -0.2), dvec3(0.0, 1.0, 0.0), dvec3(0.05, -0.1, 0.0), dvec3(3.0, 1.0, 0.0)}) {
        const dvec3 v(0.3, -1.0, 0.2);
        EXPECT_EQ((blowDryerForce<DryerAxis::Up, true, double, false>(kernel, x, v)),
                  (blowDryerForce<DryerAxis::Up, true>(kernel, x, v)));
        EXPECT_EQ((blowDryerForce<DryerAxis::Any, true, double, false>(kernel, x, v)),
                  (blowDryerForce<DryerAxis::Any, true>(kernel, x, v)));
    }
}
