// Bodies that interact, against exact oracles: two free particles on a spring (momentum,
// the centre of mass, the separation's closed form and the integrators' orders), a chain of
// masses between two fixed ends in its first normal mode, and RK4 of the coupled system equal
// to RK4 written by hand over the whole state vector.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "pba/forces.hpp"
#include "pba/particle.hpp"
#include "pba/world.hpp"

using namespace pba;

namespace {

constexpr double kK = 10.0;   // stiffness, N/m
constexpr double kM = 1.0;    // each mass, kg
constexpr double kL = 1.0;    // rest length, m
constexpr double kS0 = 1.2;   // initial separation, m
constexpr double kSdot0 = 0.4; // initial rate of separation, m/s
const dvec3 kComVelocity(0.3, 0.1, -0.2);

Particle particleAt(const dvec3& pos, const dvec3& vel, Integrator integrator, double mass = kM)
{
    Particle p;
    p.setPos(pos);
    p.setVel(vel);
    p.setMass(mass);
    p.setIntegrator(integrator);
    return p;
}

/// Two equal masses on the x axis joined by a spring, no gravity: the centre of mass moves at
/// kComVelocity, the separation oscillates along x.
World pairWorld(Integrator integrator, double damping = 0.0)
{
    World world;
    world.addParticle(particleAt(dvec3(-kS0 / 2, 0, 0), kComVelocity - dvec3(kSdot0 / 2, 0, 0), integrator));
    world.addParticle(particleAt(dvec3(kS0 / 2, 0, 0), kComVelocity + dvec3(kSdot0 / 2, 0, 0), integrator));
    world.addForce(std::make_unique<TwoBodySpring>(0, 1, kK, kL, damping));
    return world;
}

/// The separation's exact solution: the relative coordinate is an oscillator of the reduced
/// mass m/2, so omega = sqrt(2 k / m).
double exactSeparation(double t)
{
    const double w = std::sqrt(2.0 * kK / kM);
    return kL + (kS0 - kL) * std::cos(w * t) + kSdot0 / w * std::sin(w * t);
}

dvec3 momentum(const World& world)
{
    dvec3 p(0.0);
    for (std::size_t i = 0; i < world.bodyCount(); ++i)
        p += world.body(i).getMass() * world.body(i).getVel();
    return p;
}

/// Largest error of the separation over [0, T] (a maximum cannot pass through zero by accident).
double separationError(Integrator integrator, double dt, double T)
{
    World world = pairWorld(integrator);
    double worst = 0.0;
    const int steps = static_cast<int>(std::lround(T / dt));
    for (int n = 0; n < steps; ++n) {
        world.step(dt);
        const double s = glm::length(world.body(1).getPos() - world.body(0).getPos());
        worst = std::max(worst, std::abs(s - exactSeparation(world.time())));
    }
    return worst;
}

} // namespace

TEST(Coupled, MomentumIsConservedAndTheCentreOfMassMovesUniformly)
{
    for (const Integrator integrator : kAllIntegrators) {
        SCOPED_TRACE(std::string(integratorName(integrator)));
        World world = pairWorld(integrator, 0.7); // damping too: it acts on the relative velocity only
        const dvec3 p0 = momentum(world);
        const dvec3 com0 = 0.5 * (world.body(0).getPos() + world.body(1).getPos());
        for (int n = 0; n < 2000; ++n)
            world.step(0.005);
        const dvec3 p = momentum(world);
        EXPECT_NEAR(p.x, p0.x, 1e-13);
        EXPECT_NEAR(p.y, p0.y, 1e-13);
        EXPECT_NEAR(p.z, p0.z, 1e-13);
        const dvec3 com = 0.5 * (world.body(0).getPos() + world.body(1).getPos());
        const dvec3 expected = com0 + kComVelocity * world.time();
        EXPECT_NEAR(com.x, expected.x, 1e-11);
        EXPECT_NEAR(com.y, expected.y, 1e-11);
        EXPECT_NEAR(com.z, expected.z, 1e-11);
        EXPECT_TRUE(world.isCoupled(0) && world.isCoupled(1));
    }
}

TEST(Coupled, TheSeparationOscillatesAtSqrtTwoKOverM)
{
    // Accurate to the integrator's order over two periods...
    const double period = 2.0 * std::numbers::pi / std::sqrt(2.0 * kK / kM);
    EXPECT_LT(separationError(Integrator::RK4, 0.001, 2 * period), 1e-10);
    EXPECT_LT(separationError(Integrator::VelocityVerlet, 0.001, 2 * period), 1e-4);
    // ... and converging at it: halving dt divides the error by 2^order.
    for (const Integrator integrator : {Integrator::VelocityVerlet, Integrator::RK4}) {
        const double coarse = separationError(integrator, 0.01, 2 * period);
        const double fine = separationError(integrator, 0.005, 2 * period);
        const double order = std::log2(coarse / fine);
        EXPECT_NEAR(order, integratorOrder(integrator), 0.25) << integratorName(integrator);
    }
}

TEST(Coupled, TheSpringsEnergyIsCountedOnceAndSplitBetweenItsEnds)
{
    World world = pairWorld(Integrator::RK4);
    const double stretch = kS0 - kL;
    EXPECT_DOUBLE_EQ(world.totalPotentialEnergy(), 0.5 * kK * stretch * stretch);
    EXPECT_DOUBLE_EQ(world.potentialEnergy(0), 0.25 * kK * stretch * stretch);
    EXPECT_DOUBLE_EQ(world.potentialEnergy(0) + world.potentialEnergy(1), world.totalPotentialEnergy());
    // Undamped RK4 with a small step keeps the total energy.
    const double e0 = world.totalEnergy();
    for (int n = 0; n < 1000; ++n)
        world.step(0.001);
    EXPECT_NEAR(world.totalEnergy(), e0, 1e-9 * e0);
}

TEST(Coupled, AChainBetweenFixedEndsKeepsItsFirstNormalMode)
{
    // N masses a apart between fixed ends, springs at rest: the longitudinal motion is linear, and
    // u_j(t) = A sin(j pi / (N + 1)) cos(w1 t), w1 = 2 sqrt(k / m) sin(pi / (2 (N + 1))).
    constexpr int kN = 6;
    constexpr double kA = 0.05;
    constexpr double kSpacing = 0.5;
    World world;
    auto rest = [](int j) { return dvec3(j * kSpacing, 1.0, 0.0); };
    auto shape = [](int j) { return std::sin(j * std::numbers::pi / (kN + 1)); };
    for (int j = 0; j <= kN + 1; ++j) {
        const double u = (j == 0 || j == kN + 1) ? 0.0 : kA * shape(j);
        Particle p = particleAt(rest(j) + dvec3(u, 0, 0), dvec3(0.0), Integrator::RK4);
        p.setFixed(j == 0 || j == kN + 1);
        world.addParticle(p);
    }
    for (int j = 0; j <= kN; ++j)
        world.addForce(std::make_unique<TwoBodySpring>(std::size_t(j), std::size_t(j + 1), kK, kSpacing, 0.0));
    // The moving masses form one group (joined through each other, not through the fixed ends).
    EXPECT_EQ(world.coupledGroup(3).size(), std::size_t(kN));
    EXPECT_EQ(world.coupledGroup(0), std::vector<std::size_t>{0});
    const double w1 = 2.0 * std::sqrt(kK / kM) * std::sin(std::numbers::pi / (2.0 * (kN + 1)));
    const double period = 2.0 * std::numbers::pi / w1;
    const double dt = period / 2000.0;
    double worst = 0.0;
    for (int n = 1; n <= 4000; ++n) { // two periods
        world.step(dt);
        for (int j = 1; j <= kN; ++j) {
            const dvec3 x = world.body(std::size_t(j)).getPos();
            const double exact = kA * shape(j) * std::cos(w1 * world.time());
            worst = std::max(worst, std::abs(x.x - rest(j).x - exact));
            EXPECT_EQ(x.y, 1.0);
            if (n == 1000) { // half a period: every mass at minus its start, the mode's shape kept
                EXPECT_NEAR(x.x - rest(j).x, -kA * shape(j), 1e-9);
            }
        }
    }
    EXPECT_LT(worst, 1e-9); // against a 5 cm amplitude
    EXPECT_EQ(world.body(0).getPos(), rest(0));
    EXPECT_EQ(world.body(kN + 1).getPos(), rest(kN + 1));
}

namespace {

/// A triangle of three unequal masses joined by damped springs, in gravity and drag.
struct Triangle {
    std::array<double, 3> mass{1.0, 2.0, 0.5};
    std::array<dvec3, 3> pos{dvec3(0, 1, 0), dvec3(1.1, 1.2, 0.1), dvec3(0.4, 2.0, -0.3)};
    std::array<dvec3, 3> vel{dvec3(0.5, 0, 0), dvec3(0, -0.3, 0.2), dvec3(-0.1, 0.4, 0)};
    struct Link {
        std::size_t a, b;
        double k, L, c;
    };
    std::array<Link, 3> links{Link{0, 1, 40.0, 1.0, 0.3}, Link{1, 2, 25.0, 0.9, 0.0}, Link{2, 0, 60.0, 1.1, 0.5}};
    dvec3 g{0, -9.81, 0};
    double drag = 0.2;
};

/// The same system's derivative written out over a flat vector y = (x0, x1, x2, v0, v1, v2).
std::vector<double> derivative(const Triangle& t, const std::vector<double>& y)
{
    auto at = [&](std::size_t base, std::size_t i) { return dvec3(y[base + 3 * i], y[base + 3 * i + 1], y[base + 3 * i + 2]); };
    std::array<dvec3, 3> f;
    for (std::size_t i = 0; i < 3; ++i)
        f[i] = t.mass[i] * t.g - t.drag * at(9, i);
    for (const auto& l : t.links) {
        const dvec3 d = at(0, l.b) - at(0, l.a);
        const double len = glm::length(d);
        const dvec3 u = d / len;
        const dvec3 onB = -(l.k * (len - l.L) + l.c * glm::dot(at(9, l.b) - at(9, l.a), u)) * u;
        f[l.b] += onB;
        f[l.a] -= onB;
    }
    std::vector<double> dy(18);
    for (std::size_t i = 0; i < 3; ++i)
        for (int c = 0; c < 3; ++c) {
            dy[3 * i + std::size_t(c)] = y[9 + 3 * i + std::size_t(c)];
            dy[9 + 3 * i + std::size_t(c)] = f[i][c] / t.mass[i];
        }
    return dy;
}

/// Textbook RK4 on y' = f(y).
void rk4Flat(const Triangle& t, std::vector<double>& y, double dt)
{
    auto axpy = [](const std::vector<double>& a, double s, const std::vector<double>& b) {
        std::vector<double> r(a.size());
        for (std::size_t i = 0; i < a.size(); ++i)
            r[i] = a[i] + s * b[i];
        return r;
    };
    const auto k1 = derivative(t, y);
    const auto k2 = derivative(t, axpy(y, dt / 2, k1));
    const auto k3 = derivative(t, axpy(y, dt / 2, k2));
    const auto k4 = derivative(t, axpy(y, dt, k3));
    for (std::size_t i = 0; i < y.size(); ++i)
        y[i] += dt / 6 * (k1[i] + 2 * k2[i] + 2 * k3[i] + k4[i]);
}

} // namespace

TEST(Coupled, Rk4OfTheCoupledSystemIsRk4OfTheWholeStateVector)
{
    const Triangle t;
    World world;
    world.addForce(std::make_unique<Gravity>(t.g));
    world.addForce(std::make_unique<Drag>(t.drag));
    std::vector<double> y(18);
    for (std::size_t i = 0; i < 3; ++i) {
        world.addParticle(particleAt(t.pos[i], t.vel[i], Integrator::RK4, t.mass[i]));
        for (int c = 0; c < 3; ++c) {
            y[3 * i + std::size_t(c)] = t.pos[i][c];
            y[9 + 3 * i + std::size_t(c)] = t.vel[i][c];
        }
    }
    for (const auto& l : t.links)
        world.addForce(std::make_unique<TwoBodySpring>(l.a, l.b, l.k, l.L, l.c));
    // A large step, where body-by-body RK4 (each body's stages against the others' start
    // states) would differ from the system's RK4 well above rounding.
    const double dt = 0.02;
    for (int n = 0; n < 200; ++n) {
        world.step(dt);
        rk4Flat(t, y, dt);
    }
    for (std::size_t i = 0; i < 3; ++i)
        for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(world.body(i).getPos()[c], y[3 * i + std::size_t(c)], 1e-12);
            EXPECT_NEAR(world.body(i).getVel()[c], y[9 + 3 * i + std::size_t(c)], 1e-11);
        }
}

TEST(Coupled, TheAccelerationIsTheStepsFirstEvaluation)
{
    // A coupled pair and an independent body: each keeps the acceleration at its start state.
    World world = pairWorld(Integrator::VelocityVerlet);
    world.addForce(std::make_unique<Gravity>(dvec3(0, -9.81, 0)));
    world.addParticle(particleAt(dvec3(3, 1, 0), dvec3(1, 0, 0), Integrator::RK4));
    std::vector<dvec3> expected;
    for (std::size_t i = 0; i < world.bodyCount(); ++i)
        expected.push_back(world.acceleration(i, world.body(i).getPos(), world.body(i).getVel()));
    world.step(0.01);
    for (std::size_t i = 0; i < world.bodyCount(); ++i)
        EXPECT_EQ(world.body(i).getAcc(), expected[i]) << i;
    EXPECT_FALSE(world.isCoupled(2));
}

TEST(Coupled, AMixedGroupIsRefusedBeforeAnythingMoves)
{
    World world = pairWorld(Integrator::RK4);
    world.body(1).setIntegrator(Integrator::SemiImplicitEuler);
    const dvec3 start = world.body(0).getPos();
    EXPECT_THROW(world.step(0.01), std::invalid_argument);
    EXPECT_EQ(world.body(0).getPos(), start);
    // A fixed end puts no condition on the integrators.
    world.body(1).setFixed(true);
    EXPECT_NO_THROW(world.step(0.01));
}

TEST(Coupled, CoupledBodiesStayAboveTheGround)
{
    for (const CollisionResponse response : kAllCollisionResponses) {
        World world = pairWorld(Integrator::SemiImplicitEuler, 0.5);
        world.addForce(std::make_unique<Gravity>(dvec3(0, -9.81, 0)));
        world.body(0).setPos(dvec3(-0.6, 0.5, 0));
        world.body(1).setPos(dvec3(0.6, 1.5, 0));
        world.setGround(0.0);
        world.setCollisionResponse(response);
        for (int n = 0; n < 1000; ++n) {
            world.step(0.005);
            ASSERT_GE(world.body(0).getPos().y, 0.0) << collisionResponseName(response);
            ASSERT_GE(world.body(1).getPos().y, 0.0) << collisionResponseName(response);
        }
        EXPECT_GT(world.bounceCount(0) + world.bounceCount(1), 0u);
    }
}

TEST(Coupled, ACopiedWorldStepsLikeTheOriginal)
{
    World a = pairWorld(Integrator::RK4, 0.3);
    World b = a; // the default copy: bodies and forces cloned
    ASSERT_NE(&a.force(0), &b.force(0));
    for (int n = 0; n < 100; ++n) {
        a.step(0.01);
        b.step(0.01);
    }
    EXPECT_EQ(a.body(0).getPos(), b.body(0).getPos());
    EXPECT_EQ(a.body(1).getVel(), b.body(1).getVel());
    b = a;
    EXPECT_EQ(b.stepCount(), a.stepCount());
}

TEST(Coupled, ASpringToAFixedParticleIsTheAnchoredSpring)
{
    // One kernel for both forms, and the integrators' one implementation for a body (Vec3)
    // and for a group (Vec3Array): the same arithmetic, so the same numbers to the last bit.
    for (const Integrator integrator : kAllIntegrators) {
        const dvec3 anchor(0.2, 3.0, -0.1);
        World anchored;
        World joined;
        for (World* w : {&anchored, &joined}) {
            w->addForce(std::make_unique<Gravity>(dvec3(0, -9.81, 0)));
            w->addParticle(particleAt(dvec3(0.5, 1.8, 0.3), dvec3(0.4, 0, 0), integrator, 0.7));
        }
        anchored.addForce(std::make_unique<Spring>(0, anchor, 30.0, 0.8, 0.4));
        Particle end = particleAt(anchor, dvec3(0.0), integrator);
        end.setFixed(true);
        joined.addParticle(end);
        joined.addForce(std::make_unique<TwoBodySpring>(1, 0, 30.0, 0.8, 0.4));
        ASSERT_TRUE(joined.isCoupled(0));
        for (int n = 0; n < 300; ++n) {
            anchored.step(0.01);
            joined.step(0.01);
        }
        EXPECT_EQ(anchored.body(0).getPos(), joined.body(0).getPos()) << integratorName(integrator);
        EXPECT_EQ(anchored.body(0).getVel(), joined.body(0).getVel()) << integratorName(integrator);
        EXPECT_EQ(joined.body(1).getPos(), anchor);
    }
}

TEST(Coupled, ANonFiniteGroupIsReportedAndRolledBack)
{
    // Forward Euler far beyond its stability limit on a stiff pair: the state overflows.
    World world = pairWorld(Integrator::ForwardEuler);
    world.addForce(std::make_unique<TwoBodySpring>(0, 1, 1e12, kL, 0.0));
    State before;
    try {
        for (int n = 0; n < 10000; ++n) {
            before = world.body(0).getState();
            world.step(0.1);
        }
        FAIL() << "expected a NonFiniteStateError";
    } catch (const NonFiniteStateError& e) {
        EXPECT_EQ(world.body(0).getPos(), before.pos);
        EXPECT_EQ(world.body(0).getVel(), before.vel);
    }
}
