// Rotation of a free rigid body against exact solutions: the symmetric top's precession, the
// conservation of energy and |L|, each method's order, the tennis racket's flip period from
// the complete elliptic integral, and the implicit gyroscopic step's bounded energy.
#include "pba/rigid_body.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <vector>

using namespace pba;

namespace {

const auto kNoTorque = [](const dquat&, const dvec3&) { return dvec3(0.0); };

/// Body-frame angular velocity of a rotational state.
dvec3 bodyOmega(const Rotation& s, const dmat3& inverseInertia)
{
    return glm::transpose(glm::mat3_cast(s.orientation)) * angularVelocity(s.orientation, inverseInertia, s.momentum);
}

double energy(const Rotation& s, const dmat3& inverseInertia)
{
    return 0.5 * glm::dot(angularVelocity(s.orientation, inverseInertia, s.momentum), s.momentum);
}

/// A free body spun with body-frame angular velocity w at the identity orientation.
Rotation spun(const dmat3& inertia, const dvec3& w) { return Rotation{dquat(1.0, 0.0, 0.0, 0.0), inertia * w}; }

Rotation run(Integrator integrator, Rotation s, const dmat3& inverseInertia, double dt, int steps)
{
    for (int n = 0; n < steps; ++n)
        integrateRotation(integrator, s, inverseInertia, dt, kNoTorque);
    return s;
}

} // namespace

TEST(RigidBody, SettersKeepTheStateConsistent)
{
    RigidBody box(boxMassProperties(dvec3(1.0, 2.0, 3.0), 1.0));
    EXPECT_DOUBLE_EQ(box.getMass(), 6.0);
    box.setOrientation(dquat(2.0, 0.0, 0.0, 0.0));
    EXPECT_DOUBLE_EQ(glm::length(box.getOrientation()), 1.0);
    box.setOrientation(glm::angleAxis(0.7, glm::normalize(dvec3(1.0, 2.0, -1.0))));
    const dvec3 omega(0.3, -1.2, 2.0);
    box.setAngularVelocity(omega);
    const dvec3 back = box.getAngularVelocity();
    EXPECT_NEAR(back.x, omega.x, 1e-12);
    EXPECT_NEAR(back.y, omega.y, 1e-12);
    EXPECT_NEAR(back.z, omega.z, 1e-12);
    EXPECT_NEAR(box.getRotationalKineticEnergy(), 0.5 * glm::dot(omega, box.getAngularMomentum()), 1e-12);
    EXPECT_THROW(box.setOrientation(dquat(0.0, 0.0, 0.0, 0.0)), std::invalid_argument);
    MassProperties flat = boxMassProperties(dvec3(1.0), 1.0);
    flat.inertia[2][2] = -1.0;
    EXPECT_THROW(box.setMassProperties(flat), std::invalid_argument);
    const std::unique_ptr<Body> copy = box.clone();
    EXPECT_EQ(static_cast<const RigidBody&>(*copy).getAngularMomentum(), box.getAngularMomentum());
}

// A cylinder (symmetric about its y axis) spinning freely: in the body frame omega turns about
// y at Omega = (I_y - I_x) / I_x omega_y (from Euler's equations: omega_x' = Omega omega_z,
// omega_z' = -Omega omega_x), and L stays where it is in the world.
TEST(RigidBody, SymmetricTopPrecessesAsTheClosedFormSays)
{
    const MassProperties can = cylinderMassProperties(0.3, 1.0, 1000.0);
    const dmat3 inverse = glm::inverse(can.inertia);
    const dvec3 w0(0.4, 5.0, -0.3);
    const Rotation start = spun(can.inertia, w0);
    const double omega = (can.inertia[1][1] - can.inertia[0][0]) / can.inertia[0][0] * w0.y;
    const double t = 2.0;
    const Rotation end = run(Integrator::RK4, start, inverse, 1e-3, 2000);
    const dvec3 w = bodyOmega(end, inverse);
    EXPECT_NEAR(w.x, w0.x * std::cos(omega * t) + w0.z * std::sin(omega * t), 1e-9);
    EXPECT_NEAR(w.z, w0.z * std::cos(omega * t) - w0.x * std::sin(omega * t), 1e-9);
    EXPECT_NEAR(w.y, w0.y, 1e-9);
    EXPECT_NEAR(glm::length(end.momentum - start.momentum), 0.0, 1e-12); // no torque: L is constant
}

// Each method's global error on a torque-free asymmetric box over one second falls with dt at
// its order: 1, 1, 2, 2 and 4 (ratio of errors at dt and dt/2, as a power of two).
TEST(RigidBody, EachMethodConvergesAtItsOrder)
{
    const MassProperties box = boxMassProperties(dvec3(0.2, 0.5, 1.0), 500.0);
    const dmat3 inverse = glm::inverse(box.inertia);
    const Rotation start = spun(box.inertia, dvec3(0.5, 3.0, 0.8));
    const Rotation exact = run(Integrator::RK4, start, inverse, 1.0 / 16000.0, 16000);
    auto error = [&](Integrator integrator, int steps) {
        const Rotation s = run(integrator, start, inverse, 1.0 / steps, steps);
        // The orientation's error (q and -q are one rotation).
        const dquat d = glm::dot(s.orientation, exact.orientation) < 0.0 ? -s.orientation : s.orientation;
        return glm::length(d - exact.orientation);
    };
    for (const auto& [integrator, order, steps] :
         std::vector<std::tuple<Integrator, int, int>>{{Integrator::ForwardEuler, 1, 4000},
                                                       {Integrator::SemiImplicitEuler, 1, 4000},
                                                       {Integrator::VelocityVerlet, 2, 400},
                                                       {Integrator::Splitting, 2, 400},
                                                       {Integrator::RK4, 4, 100}}) {
        const double measured = std::log2(error(integrator, steps) / error(integrator, 2 * steps));
        EXPECT_NEAR(measured, order, 0.15) << integratorName(integrator);
    }
}

// The tennis racket theorem: spun near its intermediate axis, a free box flips over and back.
// With I1 < I2 < I3, energy E and L^2 = |L|^2 (here L^2 < 2 E I2), omega_2 goes as an elliptic
// sn whose period is T = 4 K(k) sqrt(I1 I2 I3 / ((I2 - I1)(2 E I3 - L^2))), with
// k^2 = (I3 - I2)(L^2 - 2 E I1) / ((I2 - I1)(2 E I3 - L^2)): it changes sign every T / 2.
TEST(RigidBody, TennisRacketFlipsAtTheEllipticIntegralsPeriod)
{
    const MassProperties box = boxMassProperties(dvec3(0.1, 0.4, 0.9), 800.0);
    const double i1 = box.inertia[0][0], i2 = box.inertia[1][1], i3 = box.inertia[2][2];
    ASSERT_LT(i3, i2); // the long side along z has the smallest moment: order them as I_z < I_y < I_x
    const dmat3 inverse = glm::inverse(box.inertia);
    // About y, the intermediate axis, nudged towards z (so that L^2 < 2 E I2, the formula's case).
    const Rotation start = spun(box.inertia, dvec3(0.0, 4.0, 0.05));
    const double e = energy(start, inverse);
    const double l2 = glm::dot(start.momentum, start.momentum);
    // Ordered moments a < b < c (here z, y, x).
    const double a = i3, b = i2, c = i1;
    ASSERT_LT(l2, 2.0 * e * b);
    const double k2 = (c - b) * (l2 - 2.0 * e * a) / ((b - a) * (2.0 * e * c - l2));
    const double period = 4.0 * std::comp_ellint_1(std::sqrt(k2)) * std::sqrt(a * b * c / ((b - a) * (2.0 * e * c - l2)));
    // Step with RK4 and time the sign changes of omega_y, interpolating within the step.
    Rotation s = start;
    const double dt = 1e-4;
    std::vector<double> flips;
    double before = bodyOmega(s, inverse).y;
    for (int n = 1; n <= int(2.2 * period / dt); ++n) {
        integrateRotation(Integrator::RK4, s, inverse, dt, kNoTorque);
        const double now = bodyOmega(s, inverse).y;
        if ((before > 0.0) != (now > 0.0))
            flips.push_back(dt * (n - 1 + before / (before - now)));
        before = now;
    }
    ASSERT_GE(flips.size(), 3u);
    for (std::size_t f = 1; f < flips.size(); ++f)
        EXPECT_NEAR(flips[f] - flips[f - 1], period / 2.0, 0.01 * period / 2.0) << "flip " << f;
}

// At dt = 0.05 a fast-spinning asymmetric box gains energy under forward Euler; the implicit
// gyroscopic step keeps it bounded (it loses a little).
TEST(RigidBody, ImplicitGyroscopicStepKeepsEnergyBoundedAtLargeDt)
{
    const MassProperties box = boxMassProperties(dvec3(0.2, 0.5, 1.0), 500.0);
    const dmat3 inverse = glm::inverse(box.inertia);
    const Rotation start = spun(box.inertia, dvec3(2.0, 6.0, 1.0));
    const double e0 = energy(start, inverse);
    Rotation implicit = start, explicitEuler = start;
    double highest = e0;
    for (int n = 0; n < 1000; ++n) {
        implicitGyroscopicStep(implicit, box.inertia, inverse, dvec3(0.0), 0.05);
        integrateRotation(Integrator::ForwardEuler, explicitEuler, inverse, 0.05, kNoTorque);
        highest = std::max(highest, energy(implicit, inverse));
    }
    EXPECT_LE(highest, e0 * (1.0 + 1e-9));
    EXPECT_GT(energy(implicit, inverse), 0.2 * e0); // bounded, not stopped
    EXPECT_GT(energy(explicitEuler, inverse), 2.0 * e0);
}

// The splitting's free flow is a product of rotations that each leave L fixed in space: L is not
// touched, so without a torque it is the start's to the bit, step after step, at any dt.
TEST(Splitting, KeepsAngularMomentumToTheBitWithoutATorque)
{
    const MassProperties box = boxMassProperties(dvec3(0.2, 0.5, 1.0), 500.0);
    const dmat3 inverse = glm::inverse(box.inertia);
    Rotation s = spun(box.inertia, dvec3(2.0, 6.0, 1.0));
    const dvec3 l0 = s.momentum;
    for (int n = 0; n < 2000; ++n) {
        integrateRotation(Integrator::Splitting, s, inverse, 0.05, kNoTorque);
        ASSERT_EQ(s.momentum, l0) << "step " << n;
    }
    EXPECT_NEAR(glm::length(s.orientation), 1.0, 1e-15);
}

// Symplectic and time-reversible: its energy error swings but stays bounded at a dt where forward
// Euler's grows without end (the same box and dt as the implicit gyroscopic step's test, which
// loses energy instead). The bound, for the splitting's second order, is of order (omega dt)^2.
TEST(Splitting, KeepsEnergyBoundedAtLargeDtWithoutLosingIt)
{
    const MassProperties box = boxMassProperties(dvec3(0.2, 0.5, 1.0), 500.0);
    const dmat3 inverse = glm::inverse(box.inertia);
    Rotation s = spun(box.inertia, dvec3(2.0, 6.0, 1.0));
    const double e0 = energy(s, inverse);
    double worst = 0.0, late = 0.0;
    for (int n = 0; n < 20000; ++n) {
        integrateRotation(Integrator::Splitting, s, inverse, 0.05, kNoTorque);
        const double drift = std::abs(energy(s, inverse) / e0 - 1.0);
        worst = std::max(worst, drift);
        if (n >= 19000)
            late = std::max(late, drift);
    }
    EXPECT_LT(worst, 0.05);
    EXPECT_GT(late, 0.1 * worst); // the error swings, it does not decay (no dissipation) ...
    EXPECT_LT(late, 1.05 * worst); // ... and it does not grow
}

// The tennis racket theorem at dt = 0.05 over 1,000 s (issue 64's target): |L| to 1e-12, the
// energy within 1% and the flips at the elliptic integral's period within 2%.
TEST(Splitting, TennisRacketAtALargeDtKeepsItsFlipAndItsInvariants)
{
    const MassProperties box = boxMassProperties(dvec3(0.1, 0.6, 0.3), 500.0);
    const dmat3 inverse = glm::inverse(box.inertia);
    Rotation s = spun(box.inertia, dvec3(0.0, 0.05, 6.0)); // the tennis-racket scene's box and spin
    const double e0 = energy(s, inverse), l0 = glm::length(s.momentum);
    // The moments: y smallest, z intermediate, x largest; L^2 < 2 E I_z.
    const double a = box.inertia[1][1], b = box.inertia[2][2], c = box.inertia[0][0];
    const double l2 = l0 * l0;
    const double k2 = (c - b) * (l2 - 2.0 * e0 * a) / ((b - a) * (2.0 * e0 * c - l2));
    const double period = 4.0 * std::comp_ellint_1(std::sqrt(k2)) * std::sqrt(a * b * c / ((b - a) * (2.0 * e0 * c - l2)));
    const double dt = 0.05;
    double worstEnergy = 0.0, worstMomentum = 0.0, before = bodyOmega(s, inverse).z;
    std::vector<double> flips;
    for (int n = 1; n <= 20000; ++n) {
        integrateRotation(Integrator::Splitting, s, inverse, dt, kNoTorque);
        worstEnergy = std::max(worstEnergy, std::abs(energy(s, inverse) / e0 - 1.0));
        worstMomentum = std::max(worstMomentum, std::abs(glm::length(s.momentum) / l0 - 1.0));
        const double now = bodyOmega(s, inverse).z;
        if ((before > 0.0) != (now > 0.0))
            flips.push_back(dt * (n - 1 + before / (before - now)));
        before = now;
    }
    EXPECT_LT(worstMomentum, 1e-12);
    EXPECT_LT(worstEnergy, 0.01);
    ASSERT_GE(flips.size(), 300u);
    const double measured = 2.0 * (flips.back() - flips.front()) / double(flips.size() - 1);
    EXPECT_NEAR(measured, period, 0.02 * period);
}

// A body whose inertia is not diagonal in its own frame (a mesh's) turns about its principal
// axes: the same motion as the diagonal body seen in its principal frame.
TEST(Splitting, DiagonalisesAnInertiaThatIsNotDiagonal)
{
    const MassProperties box = boxMassProperties(dvec3(0.2, 0.5, 1.0), 500.0);
    const dquat turn = glm::angleAxis(0.7, glm::normalize(dvec3(1.0, 2.0, -0.5))); // principal -> body frame
    const dmat3 r = glm::mat3_cast(turn);
    const dmat3 tilted = r * box.inertia * glm::transpose(r);
    const dvec3 l(3.0, -1.0, 2.0);
    // q_body = q_principal * conj(turn): the same world orientation of the principal frame.
    const dquat principal = freeRotation(dquat(1.0, 0.0, 0.0, 0.0), l, box.inertia, 0.05);
    const dquat body = freeRotation(glm::conjugate(turn), l, tilted, 0.05);
    const dquat expected = principal * glm::conjugate(turn);
    const double distance = std::min(glm::length(body - expected), glm::length(body + expected));
    EXPECT_LT(distance, 1e-12);
}
