// The blow dryer's field against its definition, and its dynamics against the harmonic
// oscillator it becomes on the axis.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "pba/blow_dryer.hpp"
#include "pba/forces.hpp"
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
