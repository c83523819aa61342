#include "backward_euler.hpp"

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

/// Solves the dense system a x = r (a row-major, r.size() rows) by Gaussian elimination with
/// partial pivoting; r becomes x. A few bodies' six velocities: a handful of rows.
void solveDense(std::vector<double>& a, std::vector<double>& r)
{
    const std::size_t n = r.size();
    for (std::size_t c = 0; c < n; ++c) {
        std::size_t pivot = c;
        for (std::size_t i = c + 1; i < n; ++i)
            if (std::abs(a[i * n + c]) > std::abs(a[pivot * n + c]))
                pivot = i;
        if (pivot != c) {
            for (std::size_t j = 0; j < n; ++j)
                std::swap(a[c * n + j], a[pivot * n + j]);
            std::swap(r[c], r[pivot]);
        }
        for (std::size_t i = c + 1; i < n; ++i) {
            const double f = a[i * n + c] / a[c * n + c];
            for (std::size_t j = c; j < n; ++j)
                a[i * n + j] -= f * a[c * n + j];
            r[i] -= f * r[c];
        }
    }
    for (std::size_t c = n; c-- > 0;) {
        for (std::size_t j = c + 1; j < n; ++j)
            r[c] -= a[c * n + j] * r[j];
        r[c] /= a[c * n + c];
    }
}

} // namespace

void BackwardEuler::step(const SpringSystem& springs, std::span<const double> mass, std::span<dvec3> x,
                         std::span<dvec3> v, std::span<const dvec3> force, double dt, std::span<const dvec3> heldOn,
                         const Bearers& bearers)
{
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
    const auto startHeld = [&] {
        if (m_held)
            forEachIndex(n, [&](std::size_t p) {
                m_dv[p] = filtered(p, m_dv[p]) + (heldSpeed(p, bearers) - glm::dot(m_normal[p], v[p])) * m_normal[p];
            });
    };
    startHeld();
    m_iterations = 0;
    double scale = solve(springs, mass);
    // Each round lets go of every member its surface pulls; a few rounds settle any sheet (a
    // member let go of in the last still ends held this step, and is free the next).
    constexpr int kReleaseRounds = 4;
    for (int round = 0; m_held && round < kReleaseRounds && releasePulled(springs, mass); ++round)
        scale = solve(springs, mass);
    // The bearers with the sheet, from the guess, again without any member they pull.
    if (m_held && !bearers.bodies.empty()) {
        m_guess.assign(bearers.bodies.begin(), bearers.bodies.end());
        for (int round = 0; round < kReleaseRounds && solveBearers(springs, mass, bearers); ++round) {
            std::copy(m_guess.begin(), m_guess.end(), bearers.bodies.begin());
            startHeld();
            scale = solve(springs, mass);
        }
    }
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
        const dvec3 residual = dt * (m_otherForce[p] + springSum(springs, m_perSpring, p)) - mass[p] * (v[p] - m_v0[p]);
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
        return 0.5 * mass[p] * glm::dot(change, change) - dt * glm::dot(m_otherForce[p], m_trial[p]);
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
        dmat3 diagonal(mass[p]);
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

double BackwardEuler::residualNorm(const SpringSystem& springs, std::span<const double> mass)
{
    springPass(springs, m_dv);
    return sumOf(m_dv.size(), [&](std::size_t p) {
        const dvec3 r = filtered(p, m_rhs[p] - (mass[p] * m_dv[p] + springSum(springs, m_perSpring, p)));
        return glm::dot(r, m_inverseDiagonal[p].apply(r));
    });
}

double BackwardEuler::solve(const SpringSystem& springs, std::span<const double> mass, double scaleOf)
{
    // Preconditioned conjugate gradients from the last step's dv: a motion that changes smoothly
    // changes its velocities by nearly as much from one step to the next, and the solve then starts
    // close to its answer. A p is kept by its own recurrence, A p = A z + beta A p_old, so that an
    // iteration is three passes (the springs on z, then two over the bodies) rather than four:
    // each pass on all cores waits for the slowest core at its end.
    const std::size_t n = m_rhs.size();
    m_r.resize(n);
    m_z.resize(n);
    m_p.resize(n);
    m_ap.resize(n);
    // A held member's residual and search directions are filtered (filtered), so its velocity
    // along the normal stays where the step put it.
    springPass(springs, m_dv);
    const double scale = sumOf(n, [&](std::size_t p) {
        m_r[p] = filtered(p, m_rhs[p] - (mass[p] * m_dv[p] + springSum(springs, m_perSpring, p)));
        const dvec3 rhs = filtered(p, m_rhs[p]);
        return glm::dot(rhs, m_inverseDiagonal[p].apply(rhs));
    });
    double rz = sumOf(n, [&](std::size_t p) {
        m_z[p] = filtered(p, m_inverseDiagonal[p].apply(m_r[p]));
        return glm::dot(m_r[p], m_z[p]);
    });
    m_residual = scale > 0.0 ? std::sqrt(std::max(rz, 0.0) / scale) : 0.0;
    // Done when the residual's preconditioned norm is kTolerance of the right-hand side's, or (a
    // bearer's probe, whose right-hand side is zero) of `scaleOf`. (A right-hand side that is
    // not finite stops it at once: the step's check says so.)
    const double target = kTolerance * kTolerance * (scaleOf > 0.0 ? scaleOf : scale);
    double beta = 0.0;
    for (int iteration = 0; iteration < kMaxIterations && rz > target; ++iteration) {
        springPass(springs, m_z);
        const double pap = sumOf(n, [&](std::size_t p) {
            const dvec3 az = mass[p] * m_z[p] + springSum(springs, m_perSpring, p);
            m_p[p] = m_z[p] + beta * m_p[p];
            m_ap[p] = az + beta * m_ap[p];
            return glm::dot(m_p[p], m_ap[p]);
        });
        if (!(pap > 0.0))
            break;
        const double alpha = rz / pap;
        const double next = sumOf(n, [&](std::size_t p) {
            m_dv[p] += alpha * m_p[p];
            m_r[p] -= alpha * filtered(p, m_ap[p]);
            m_z[p] = filtered(p, m_inverseDiagonal[p].apply(m_r[p]));
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
    heldImpulses(springs, mass, true, m_baseImpulse);
    const double released = sumOf(m_normal.size(), [&](std::size_t p) {
        m_push[p] = 0.0;
        if (m_normal[p] == dvec3(0.0))
            return 0.0;
        if (m_baseImpulse[p] < 0.0) {
            m_normal[p] = dvec3(0.0);
            return 1.0;
        }
        m_push[p] = m_baseImpulse[p] / mass[p];
        return 0.0;
    });
    return released > 0.0;
}

void BackwardEuler::heldImpulses(const SpringSystem& springs, std::span<const double> mass, bool withRhs,
                                 std::vector<double>& out)
{
    // What a held member's surface gives it is what its equation lacks: A dv - b, along the normal.
    springPass(springs, m_dv);
    out.resize(m_normal.size());
    forEachIndex(m_normal.size(), [&](std::size_t p) {
        const dvec3& normal = m_normal[p];
        const dvec3 given = mass[p] * m_dv[p] + springSum(springs, m_perSpring, p) - (withRhs ? m_rhs[p] : dvec3(0.0));
        out[p] = normal == dvec3(0.0) ? 0.0 : glm::dot(normal, given);
    });
}

double BackwardEuler::heldSpeed(std::size_t p, const Bearers& bearers) const
{
    if (bearers.of.empty() || bearers.of[p] == kNoBearer)
        return 0.0;
    const Bearer& b = bearers.bodies[bearers.of[p]];
    return glm::dot(m_normal[p], b.velocity + glm::cross(b.spin, bearers.arm[p]));
}

bool BackwardEuler::solveBearers(const SpringSystem& springs, std::span<const double> mass, const Bearers& bearers)
{
    const std::size_t n = m_dv.size(), dims = 6 * bearers.bodies.size();
    // Held member p's speed along its normal for a unit of bearer velocity q (three of the
    // bearer's velocity, then three of its spin): n . e, or n . (e x arm).
    const auto unitSpeed = [&](std::size_t p, std::size_t q) {
        if (m_normal[p] == dvec3(0.0) || bearers.of[p] != q / 6 || !bearers.bodies[q / 6].moves)
            return 0.0;
        dvec3 e(0.0);
        e[int(q % 3)] = 1.0;
        return glm::dot(m_normal[p], q % 6 < 3 ? e : glm::cross(e, bearers.arm[p]));
    };
    // The step with the bearers at the guess (solved already), then each of their velocities
    // alone: the pushes are linear in them.
    heldImpulses(springs, mass, true, m_baseImpulse);
    m_baseDv = m_dv;
    m_probeDv.resize(dims);
    m_probeImpulse.resize(dims);
    const double residual = m_residual;
    std::swap(m_rhs, m_savedRhs);
    m_rhs.assign(n, dvec3(0.0));
    for (std::size_t q = 0; q < dims; ++q) {
        // From the last step's answer for the same velocity: a resting body's changes little.
        // Its tolerance is kProbeTolerance of the cold start's residual (a warm start's own would
        // ask for more).
        forEachIndex(n, [&](std::size_t p) { m_dv[p] = unitSpeed(p, q) * m_normal[p]; });
        const double cold = residualNorm(springs, mass) * (kProbeTolerance / kTolerance) * (kProbeTolerance / kTolerance);
        if (m_probeDv[q].size() == n)
            forEachIndex(n, [&](std::size_t p) { m_dv[p] += filtered(p, m_probeDv[q][p]); });
        solve(springs, mass, cold);
        m_probeDv[q] = m_dv;
        heldImpulses(springs, mass, false, m_probeImpulse[q]);
    }
    std::swap(m_rhs, m_savedRhs);
    m_residual = residual;
    // Each bearer's momentum: M (U - U_alone) = -(what its members' pushes give it), the pushes
    // base + sum_q dU_q probe_q with U = U_guess + dU; so
    // (M + C) dU = M (U_alone - U_guess) - sum_p base_p s(p), C the sheet's apparent mass.
    std::vector<double> a(dims * dims, 0.0), change(dims, 0.0);
    for (std::size_t b = 0; b < bearers.bodies.size(); ++b) {
        const Bearer& body = bearers.bodies[b];
        const dvec3 spin = body.inertia * (body.aloneSpin - body.spin);
        for (std::size_t i = 0; i < 3; ++i) {
            a[(6 * b + i) * dims + 6 * b + i] = body.mass;
            change[6 * b + i] = body.moves ? body.mass * (body.aloneVelocity - body.velocity)[int(i)] : 0.0;
            change[6 * b + 3 + i] = body.moves ? spin[int(i)] : 0.0;
            for (std::size_t j = 0; j < 3; ++j)
                a[(6 * b + 3 + i) * dims + 6 * b + 3 + j] = body.inertia[int(j)][int(i)];
        }
    }
    for (std::size_t p = 0; p < n; ++p)
        for (std::size_t i = 0; i < dims; ++i)
            if (const double s = unitSpeed(p, i); s != 0.0) {
                change[i] -= s * m_baseImpulse[p];
                for (std::size_t q = 0; q < dims; ++q)
                    a[i * dims + q] += s * m_probeImpulse[q][p];
            }
    solveDense(a, change);
    for (std::size_t b = 0; b < bearers.bodies.size(); ++b)
        for (int i = 0; i < 3; ++i) {
            bearers.bodies[b].velocity[i] += change[6 * b + std::size_t(i)];
            bearers.bodies[b].spin[i] += change[6 * b + 3 + std::size_t(i)];
        }
    const double pulled = sumOf(n, [&](std::size_t p) {
        dvec3 dv = m_baseDv[p];
        double impulse = m_baseImpulse[p];
        for (std::size_t q = 0; q < dims; ++q) {
            dv += change[q] * m_probeDv[q][p];
            impulse += change[q] * m_probeImpulse[q][p];
        }
        m_dv[p] = dv;
        m_push[p] = std::max(impulse, 0.0) / mass[p];
        if (m_normal[p] == dvec3(0.0) || !(impulse < 0.0))
            return 0.0;
        m_normal[p] = dvec3(0.0);
        return 1.0;
    });
    return pulled > 0.0;
}

} // namespace pba::detail
