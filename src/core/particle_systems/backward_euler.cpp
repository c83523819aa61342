#include "particle_systems/backward_euler.hpp"

#include <algorithm>
#include <cmath>
#include <functional>

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include "parallel.hpp"

namespace pba::detail {

namespace {

/// The sum of term(i) over i < n (term may also write i's results), on all cores. The blocks and
/// the tree that adds them depend on n alone, so the sum is the same on any number of threads.
template <class F>
double sumOf(std::size_t n, F&& term)
{
    return tbb::parallel_deterministic_reduce(
        tbb::blocked_range<std::size_t>(0, n, kIndexGrain), 0.0,
        [&](const tbb::blocked_range<std::size_t>& r, double sum) {
            for (std::size_t i = r.begin(); i < r.end(); ++i)
                sum += term(i);
            return sum;
        },
        std::plus<double>());
}

/// A spring's end b's value of `values`, zero at a fixed end (a fixed end neither moves nor
/// has a velocity to change).
dvec3 atB(const SpringSystem& springs, std::size_t s, std::span<const dvec3> values)
{
    const std::uint32_t b = springs.b(s);
    return b == SpringSystem::kFixed ? dvec3(0.0) : values[b];
}

/// Member p's sum over its springs of +perSpring[s] where it is the first end and -perSpring[s]
/// where it is the second, in the springs' order.
dvec3 springSum(const SpringSystem& springs, const std::vector<dvec3>& perSpring, std::size_t p)
{
    dvec3 sum(0.0);
    for (const std::uint32_t end : springs.incident(p)) {
        const double sign = 1.0 - 2.0 * double(end & 1); // first end +1, second -1: exact
        sum += sign * perSpring[end >> 1];
    }
    return sum;
}

} // namespace

Mat6 Mat6::inverse() const
{
    // Gauss-Jordan elimination with partial pivoting on [A | I], factored once for all six
    // columns (a bearer's 6 x 6 preconditioner).
    std::array<double, 36> a = m;
    Mat6 result;
    for (std::size_t i = 0; i < 6; ++i)
        result.m[i * 7] = 1.0;
    double* r = result.m.data();
    for (std::size_t c = 0; c < 6; ++c) {
        std::size_t pivot = c;
        for (std::size_t i = c + 1; i < 6; ++i)
            if (std::abs(a[i * 6 + c]) > std::abs(a[pivot * 6 + c]))
                pivot = i;
        if (pivot != c)
            for (std::size_t j = 0; j < 6; ++j) {
                std::swap(a[c * 6 + j], a[pivot * 6 + j]);
                std::swap(r[c * 6 + j], r[pivot * 6 + j]);
            }
        const double inv = 1.0 / a[c * 6 + c];
        for (std::size_t j = 0; j < 6; ++j) {
            a[c * 6 + j] *= inv;
            r[c * 6 + j] *= inv;
        }
        for (std::size_t i = 0; i < 6; ++i) {
            const double f = a[i * 6 + c];
            if (i == c || f == 0.0)
                continue;
            for (std::size_t j = 0; j < 6; ++j) {
                a[i * 6 + j] -= f * a[c * 6 + j];
                r[i * 6 + j] -= f * r[c * 6 + j];
            }
        }
    }
    return result;
}

void BackwardEuler::step(const SpringSystem& springs, std::span<const double> mass, std::span<dvec3> x,
                         std::span<dvec3> v, std::span<const dvec3> force, double dt, std::span<const dvec3> heldOn,
                         const Bearers& bearers, std::span<const dmat3> along)
{
    m_along = along;
    const std::size_t n = x.size();
    m_x0.assign(x.begin(), x.end());
    m_v0.assign(v.begin(), v.end());
    m_held = std::any_of(heldOn.begin(), heldOn.end(), [](const dvec3& normal) { return normal != dvec3(0.0); });
    if (m_held) {
        m_normal.assign(heldOn.begin(), heldOn.end());
        m_push.assign(n, 0.0);
    }
    // Baraff and Witkin's step, linearised at the start, from the last step's dv, whose part
    // along a held member's normal is what stops it there.
    linearise(springs, mass, x, dt, v, force);
    if (m_dv.size() != n)
        m_dv.assign(n, dvec3(0.0));
    // The bearers' velocities start from their guess, and their members' along the normal with them.
    m_bearers = m_held && !bearers.bodies.empty() ? &bearers : nullptr;
    if (m_bearers)
        startBearers();
    if (m_held)
        forEachIndex(n, [&](std::size_t p) {
            m_dv[p] = filtered(p, m_dv[p]) + (heldSpeed(p) - glm::dot(m_normal[p], v[p])) * m_normal[p];
        });
    m_iterations = 0;
    double scale = solve(springs, mass);
    // Each round lets go of every member its surface pulls; a few rounds settle any sheet (a
    // member let go of in the last still ends held this step, and is free the next).
    constexpr int kReleaseRounds = 4;
    for (int round = 0; m_held && round < kReleaseRounds && releasePulled(springs, mass); ++round)
        scale = solve(springs, mass);
    if (m_bearers)
        finishBearers();
    m_bearers = nullptr; // Newton's corrections keep the bearers' velocities
    forEachIndex(n, [&](std::size_t p) { v[p] += m_dv[p]; });
    // Newton's corrections, each linearised where the last left the bodies, until the nonlinear
    // equations hold: the once-linearised step is only stable while the springs turn little in
    // a step; across a large rotation its linear springs stretch, and the energy grows.
    m_newtonIterations = 1;
    while (m_newtonIterations < kMaxNewtonIterations && correct(springs, mass, x, v, dt, scale))
        ++m_newtonIterations;
    forEachIndex(n, [&](std::size_t p) { x[p] = m_x0[p] + dt * v[p]; });
}

bool BackwardEuler::correct(const SpringSystem& springs, std::span<const double> mass, std::span<dvec3> x,
                            std::span<dvec3> v, double dt, double scale)
{
    // The equations' residual at the end of the step, -grad Phi, in the last linearisation's norm.
    const std::size_t n = x.size();
    forEachIndex(n, [&](std::size_t p) { x[p] = m_x0[p] + dt * v[p]; });
    springForces(springs, x, v);
    const double remaining = sumOf(n, [&](std::size_t p) {
        // A held member's surface takes up its residual along the normal.
        const dvec3 residual =
            dt * (m_otherForce[p] + springSum(springs, m_perSpring, p)) - massTimes(mass, p, v[p] - m_v0[p]);
        m_rhs[p] = filtered(p, residual);
        return glm::dot(m_rhs[p], m_inverseDiagonal[p].apply(m_rhs[p]));
    });
    if (!(remaining > kNewtonTolerance * kNewtonTolerance * scale))
        return false;
    linearise(springs, mass, x, dt);
    m_correction.assign(n, dvec3(0.0));
    std::swap(m_correction, m_dv); // solve from zero, keeping the step's dv for the next step
    solve(springs, mass);
    // Backtracking on Phi: the clamped matrix is positive definite, so the correction points
    // downhill, and a step short enough lowers Phi; a full step may not, far from the solution.
    const double slope = -sumOf(n, [&](std::size_t p) { return glm::dot(m_rhs[p], m_dv[p]); });
    const double start = phi(springs, mass, v, dt, 0.0);
    double step = 1.0;
    while (step > kSmallestStep && !(phi(springs, mass, v, dt, step) <= start + 1e-4 * step * slope))
        step *= 0.5;
    forEachIndex(n, [&](std::size_t p) {
        v[p] += step * m_dv[p];
        m_correction[p] += step * m_dv[p];
    });
    std::swap(m_correction, m_dv);
    return true;
}

double BackwardEuler::phi(const SpringSystem& springs, std::span<const double> mass, std::span<const dvec3> v,
                          double dt, double step)
{
    // Phi(v) = 1/2 |v - v0|_M^2 + E(x0 + dt v) + dt Psi(v) - dt f_other . v: the springs' energy E,
    // their damping's dissipation Psi = sum 1/2 c (u0 . (v_b - v_a))^2 along the start's directions.
    const std::size_t n = v.size();
    m_trial.resize(n);
    const double bodies = sumOf(n, [&](std::size_t p) {
        m_trial[p] = v[p] + step * m_dv[p];
        const dvec3 change = m_trial[p] - m_v0[p];
        return 0.5 * glm::dot(change, massTimes(mass, p, change)) - dt * glm::dot(m_otherForce[p], m_trial[p]);
    });
    return bodies + sumOf(springs.size(), [&](std::size_t s) {
        const std::uint32_t a = springs.a(s), b = springs.b(s);
        const bool fixed = b == SpringSystem::kFixed;
        const dvec3 xb = fixed ? springs.fixedPoint(s) : m_x0[b] + dt * m_trial[b];
        const double stretch = glm::length(xb - (m_x0[a] + dt * m_trial[a])) - springs.restLength(s);
        const double along = glm::dot(m_u0[s], (fixed ? dvec3(0.0) : m_trial[b]) - m_trial[a]);
        return 0.5 * springs.stiffness(s) * stretch * stretch + 0.5 * dt * springs.damping(s) * along * along;
    });
}

void BackwardEuler::springForces(const SpringSystem& springs, std::span<const dvec3> x, std::span<const dvec3> v)
{
    // Spring s's force on its first end: k (|d| - L) u + c (u0 . (v_b - v_a)) u0, the damping
    // along the start's direction u0 (springForce's at the start), so that it has a potential.
    m_perSpring.resize(springs.size());
    forEachIndex(springs.size(), [&](std::size_t s) {
        const std::uint32_t a = springs.a(s), b = springs.b(s);
        const bool fixed = b == SpringSystem::kFixed;
        const dvec3 d = (fixed ? springs.fixedPoint(s) : x[b]) - x[a];
        const double length = glm::length(d);
        const dvec3 u = length > 0.0 ? d / length : dvec3(0.0); // no direction: no force (springForce)
        const dvec3 dv = (fixed ? dvec3(0.0) : v[b]) - v[a];
        m_perSpring[s] = springs.stiffness(s) * (length - springs.restLength(s)) * u +
                         springs.damping(s) * glm::dot(m_u0[s], dv) * m_u0[s];
    });
}

void BackwardEuler::linearise(const SpringSystem& springs, std::span<const double> mass, std::span<const dvec3> x,
                              double dt, std::span<const dvec3> v0, std::span<const dvec3> f0)
{
    const std::size_t n = x.size();
    const bool start = !v0.empty();
    m_blocks.resize(springs.size());
    if (start) {
        m_u0.resize(springs.size());
        m_perSpring.resize(springs.size());
        m_startSpringForce.resize(springs.size());
    }
    // Each spring's block; at the start also its direction u0, its force on its first end, and its
    // part of the right-hand side, dt^2 K (v_a - v_b): one pass, as the springs are many.
    forEachIndex(springs.size(), [&](std::size_t s) {
        const std::uint32_t a = springs.a(s), b = springs.b(s);
        const dvec3 d = (b == SpringSystem::kFixed ? springs.fixedPoint(s) : x[b]) - x[a];
        const double length = glm::length(d);
        if (!(length > 0.0)) { // no direction: the spring gives no force here (springForce), nor a block
            m_blocks[s] = Block{};
            if (start)
                m_u0[s] = m_perSpring[s] = m_startSpringForce[s] = dvec3(0.0);
            return;
        }
        const dvec3 u = d / length;
        const double k = springs.stiffness(s);
        const double g = std::max(0.0, 1.0 - springs.restLength(s) / length);
        const double kAlong = dt * dt * k * (1.0 - g);
        m_blocks[s] = Block{u, dt * dt * k * g, kAlong + dt * springs.damping(s)};
        if (!start)
            return;
        const dvec3 dv = v0[a] - atB(springs, s, v0);
        m_u0[s] = u;
        m_startSpringForce[s] = (k * (length - springs.restLength(s)) - springs.damping(s) * glm::dot(u, dv)) * u;
        m_perSpring[s] = (dt * dt * k * g) * dv + (kAlong * glm::dot(u, dv)) * u;
    });
    m_inverseDiagonal.resize(n);
    if (start) {
        m_rhs.resize(n);
        m_otherForce.resize(n);
    }
    // Each body's diagonal block's inverse; at the start also its right-hand side dt f0 - sum
    // dt^2 K (v_a - v_b) and its forces other than the springs, which keep their start values.
    forEachIndex(n, [&](std::size_t p) {
        dmat3 diagonal = m_along.empty() ? dmat3(mass[p]) : dmat3(mass[p]) + m_along[p];
        for (const std::uint32_t end : springs.incident(p)) {
            const Block& block = m_blocks[end >> 1];
            diagonal += dmat3(block.alpha) + block.beta * glm::outerProduct(block.u, block.u);
        }
        const dmat3 inverse = glm::inverse(diagonal);
        m_inverseDiagonal[p] = Sym3{inverse[0][0], inverse[1][1], inverse[2][2], inverse[1][0], inverse[2][0], inverse[2][1]};
        if (start) {
            m_rhs[p] = dt * f0[p] - springSum(springs, m_perSpring, p);
            m_otherForce[p] = f0[p] - springSum(springs, m_startSpringForce, p);
        }
    });
}

void BackwardEuler::springPass(const SpringSystem& springs, const std::vector<dvec3>& w)
{
    forEachIndex(springs.size(), [&](std::size_t s) { m_perSpring[s] = m_blocks[s].apply(w[springs.a(s)] - atB(springs, s, w)); });
}

double BackwardEuler::solve(const SpringSystem& springs, std::span<const double> mass)
{
    // Preconditioned conjugate gradients from the last step's dv: a motion that changes smoothly
    // changes its velocities by nearly as much from one step to the next, and the solve then starts
    // close to its answer. A p is kept by its own recurrence, A p = A z + beta A p_old, so that an
    // iteration is three passes (the springs on z, then two over the bodies) rather than four:
    // each pass on all cores waits for the slowest core at its end. With bearers, their six
    // velocities each are unknowns beside the members' (the bearer's part of each vector, m_u*).
    const std::size_t n = m_rhs.size();
    m_r.resize(n);
    m_z.resize(n);
    m_p.resize(n);
    m_ap.resize(n);
    // A held member's residual and search directions are filtered (filtered), so its velocity
    // along the normal stays where the step put it, or moves with its bearer's.
    springPass(springs, m_dv);
    double scale = sumOf(n, [&](std::size_t p) {
        m_r[p] = m_rhs[p] - (massTimes(mass, p, m_dv[p]) + springSum(springs, m_perSpring, p)); // whole, for the bearers
        const dvec3 rhs = filtered(p, m_rhs[p]);
        return glm::dot(rhs, m_inverseDiagonal[p].apply(rhs));
    });
    if (m_bearers) {
        bearerResidual(m_r);
        scale += bearerScale();
    }
    forEachIndex(n, [&](std::size_t p) { m_r[p] = filtered(p, m_r[p]); });
    double rz = (m_bearers ? preconditionBearers() : 0.0) + sumOf(n, [&](std::size_t p) {
        m_z[p] = preconditioned(p);
        return glm::dot(m_r[p], m_z[p]);
    });
    m_residual = scale > 0.0 ? std::sqrt(std::max(rz, 0.0) / scale) : 0.0;
    // Done when the residual's preconditioned norm is kTolerance of the right-hand side's. (A
    // right-hand side that is not finite stops it at once: the step's check says so.)
    const double target = kTolerance * kTolerance * scale;
    double beta = 0.0;
    for (int iteration = 0; iteration < kMaxIterations && rz > target; ++iteration) {
        springPass(springs, m_z);
        double pap = sumOf(n, [&](std::size_t p) {
            const dvec3 az = massTimes(mass, p, m_z[p]) + springSum(springs, m_perSpring, p);
            m_p[p] = m_z[p] + beta * m_p[p];
            m_ap[p] = az + beta * m_ap[p];
            return glm::dot(m_p[p], m_ap[p]);
        });
        if (m_bearers)
            pap += bearerDirection(beta);
        if (!(pap > 0.0))
            break;
        const double alpha = rz / pap;
        const double bearers = m_bearers ? stepBearers(alpha) : 0.0;
        const double next = bearers + sumOf(n, [&](std::size_t p) {
            m_dv[p] += alpha * m_p[p];
            m_r[p] -= alpha * filtered(p, m_ap[p]);
            m_z[p] = preconditioned(p);
            return glm::dot(m_r[p], m_z[p]);
        });
        ++m_iterations;
        beta = next / rz;
        rz = next;
    }
    if (scale > 0.0)
        m_residual = std::sqrt(std::max(rz, 0.0) / scale);
    return scale;
}

bool BackwardEuler::releasePulled(const SpringSystem& springs, std::span<const double> mass)
{
    heldImpulses(springs, mass, m_impulse);
    const double released = sumOf(m_normal.size(), [&](std::size_t p) {
        m_push[p] = 0.0;
        if (m_normal[p] == dvec3(0.0))
            return 0.0;
        if (m_impulse[p] < 0.0) {
            m_normal[p] = dvec3(0.0);
            return 1.0;
        }
        m_push[p] = m_impulse[p] / mass[p];
        return 0.0;
    });
    return released > 0.0;
}

void BackwardEuler::heldImpulses(const SpringSystem& springs, std::span<const double> mass, std::vector<double>& out)
{
    // What a held member's surface gives it is what its equation lacks: A dv - b, along the normal.
    springPass(springs, m_dv);
    out.resize(m_normal.size());
    forEachIndex(m_normal.size(), [&](std::size_t p) {
        const dvec3& normal = m_normal[p];
        const dvec3 given = massTimes(mass, p, m_dv[p]) + springSum(springs, m_perSpring, p) - m_rhs[p];
        out[p] = normal == dvec3(0.0) ? 0.0 : glm::dot(normal, given);
    });
}

// ---- the bearers' part of the solve (see the header): a bearer's six velocities U are unknowns,
// and a member held on it moves along its normal n at s . U, s = (n, arm x n). ----

Twist BackwardEuler::along(std::size_t p) const
{
    const dvec3& n = m_normal[p];
    const dvec3 arm = m_bearers->arm[p];
    return {n, glm::cross(arm, n)};
}

double BackwardEuler::heldSpeed(std::size_t p) const
{
    if (!m_bearers || m_normal[p] == dvec3(0.0) || m_bearers->of[p] == kNoBearer)
        return 0.0;
    return dot(along(p), m_u[m_bearers->of[p]]);
}

void BackwardEuler::startBearers()
{
    const std::size_t count = m_bearers->bodies.size();
    m_u.resize(count);
    m_uAlone.resize(count);
    m_uMass.resize(count);
    for (std::size_t b = 0; b < count; ++b) {
        const Bearer& body = m_bearers->bodies[b];
        m_u[b] = body.moves ? Twist{body.velocity, body.spin} : Twist{body.aloneVelocity, body.aloneSpin};
        m_uAlone[b] = {body.aloneVelocity, body.aloneSpin};
        m_uMass[b] = {body.mass, body.inertia};
    }
    m_bearerMembers.clear();
    for (std::size_t p = 0; p < m_normal.size(); ++p)
        if (m_normal[p] != dvec3(0.0) && m_bearers->of[p] != kNoBearer && m_bearers->bodies[m_bearers->of[p]].moves)
            m_bearerMembers.push_back(std::uint32_t(p));
}

void BackwardEuler::finishBearers()
{
    for (std::size_t b = 0; b < m_u.size(); ++b) {
        m_bearers->bodies[b].velocity = m_u[b].linear;
        m_bearers->bodies[b].spin = m_u[b].angular;
    }
}

bool BackwardEuler::stillHeld(std::uint32_t p) const
{
    return m_normal[p] != dvec3(0.0);
}

void BackwardEuler::bearerResidual(const std::vector<dvec3>& residual)
{
    // -grad Phi along U: M (U_alone - U) less what the held members' pushes give the body, the
    // pushes lambda = n . (A dv - b) = -n . residual. Also each bearer's preconditioner: its mass
    // with each held member's diagonal along the normal.
    m_ru.assign(m_u.size(), Twist{});
    m_uDiagonal.resize(m_u.size());
    for (std::size_t b = 0; b < m_u.size(); ++b) {
        m_ru[b] = m_uMass[b].times(m_uAlone[b] - m_u[b]);
        m_uDiagonal[b] = Mat6(m_uMass[b]);
    }
    for (const std::uint32_t p : m_bearerMembers)
        if (stillHeld(p)) {
            const std::uint32_t b = m_bearers->of[p];
            const Twist s = along(p);
            m_ru[b] += s * glm::dot(m_normal[p], residual[p]);
            m_uDiagonal[b].addOuter(s, 1.0 / glm::dot(m_normal[p], m_inverseDiagonal[p].apply(m_normal[p])));
        }
    m_uInverse.resize(m_u.size());
    for (std::size_t b = 0; b < m_u.size(); ++b)
        m_uInverse[b] = m_uDiagonal[b].inverse();
}

double BackwardEuler::bearerScale() const
{
    // Each bearer's right-hand side, M U_alone and the held members' b along the normal, in the
    // preconditioner's norm.
    std::vector<Twist> rhs(m_u.size());
    for (std::size_t b = 0; b < m_u.size(); ++b)
        rhs[b] = m_uMass[b].times(m_uAlone[b]);
    for (const std::uint32_t p : m_bearerMembers)
        if (stillHeld(p))
            rhs[m_bearers->of[p]] += along(p) * glm::dot(m_normal[p], m_rhs[p]);
    double sum = 0.0;
    for (std::size_t b = 0; b < m_u.size(); ++b)
        sum += dot(rhs[b], m_uInverse[b].times(rhs[b]));
    return sum;
}

double BackwardEuler::preconditionBearers()
{
    m_zu.resize(m_u.size());
    double rz = 0.0;
    for (std::size_t b = 0; b < m_u.size(); ++b) {
        m_zu[b] = m_uInverse[b].times(m_ru[b]);
        rz += dot(m_ru[b], m_zu[b]);
    }
    return rz;
}

dvec3 BackwardEuler::preconditioned(std::size_t p) const
{
    // The member's own block, filtered; on a bearer, its normal part the bearer's direction's.
    const dvec3 own = filtered(p, m_inverseDiagonal[p].apply(m_r[p]));
    if (!m_bearers || m_normal[p] == dvec3(0.0) || m_bearers->of[p] == kNoBearer ||
        !m_bearers->bodies[m_bearers->of[p]].moves)
        return own;
    return own + dot(along(p), m_zu[m_bearers->of[p]]) * m_normal[p];
}

double BackwardEuler::bearerDirection(double beta)
{
    // The bearers' part of p and of H p: M p_U plus the held members' (A p) along the normal.
    // Their part of p^T H p is p_U^T M p_U: the members' pass counted p^T A p with the normal parts.
    m_pu.resize(m_u.size());
    m_apu.resize(m_u.size());
    double pap = 0.0;
    for (std::size_t b = 0; b < m_u.size(); ++b) {
        m_pu[b] = m_zu[b] + m_pu[b] * beta;
        m_apu[b] = m_uMass[b].times(m_pu[b]);
        pap += dot(m_pu[b], m_apu[b]);
    }
    for (const std::uint32_t p : m_bearerMembers)
        if (stillHeld(p))
            m_apu[m_bearers->of[p]] += along(p) * glm::dot(m_normal[p], m_ap[p]);
    return pap;
}

double BackwardEuler::stepBearers(double alpha)
{
    for (std::size_t b = 0; b < m_u.size(); ++b) {
        m_u[b] += m_pu[b] * alpha;
        m_ru[b] += m_apu[b] * -alpha;
    }
    return preconditionBearers();
}

} // namespace pba::detail
