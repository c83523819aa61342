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
dvec3 atB(const SpringSystem& springs, std::size_t s, const std::vector<dvec3>& values)
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

void BackwardEuler::step(const SpringSystem& springs, std::span<const double> mass, std::span<dvec3> x,
                         std::span<dvec3> v, std::span<const dvec3> force, double dt)
{
    setUp(springs, mass, x, v, force, dt);
    solve(springs, mass);
    forEachIndex(x.size(), [&](std::size_t p) {
        v[p] += m_dv[p];
        x[p] += v[p] * dt;
    });
}

void BackwardEuler::setUp(const SpringSystem& springs, std::span<const double> mass, std::span<const dvec3> x,
                          std::span<const dvec3> v, std::span<const dvec3> force, double dt)
{
    const std::size_t n = x.size();
    m_blocks.resize(springs.size());
    m_perSpring.resize(springs.size());
    // Each spring's block, and its part of the right-hand side, dt^2 K (v_a - v_b).
    forEachIndex(springs.size(), [&](std::size_t s) {
        const std::uint32_t a = springs.a(s), b = springs.b(s);
        const dvec3 d = (b == SpringSystem::kFixed ? springs.fixedPoint(s) : x[b]) - x[a];
        const double length = glm::length(d);
        if (!(length > 0.0)) { // no direction: the spring gives no force here (springForce), nor a block
            m_blocks[s] = Block{};
            m_perSpring[s] = dvec3(0.0);
            return;
        }
        const dvec3 u = d / length;
        const double k = springs.stiffness(s);
        const double g = std::max(0.0, 1.0 - springs.restLength(s) / length);
        Block& block = m_blocks[s];
        block.u = u;
        block.alpha = dt * dt * k * g;
        block.beta = dt * dt * k * (1.0 - g) + dt * springs.damping(s);
        const dvec3 dv = v[a] - (b == SpringSystem::kFixed ? dvec3(0.0) : v[b]);
        const double kAlong = dt * dt * k * (1.0 - g);
        m_perSpring[s] = (dt * dt * k * g) * dv + (kAlong * glm::dot(u, dv)) * u;
    });
    m_rhs.resize(n);
    m_inverseDiagonal.resize(n);
    // Each body's right-hand side dt f0 - sum dt^2 K (v_a - v_b), and its diagonal block's inverse.
    forEachIndex(n, [&](std::size_t p) {
        m_rhs[p] = dt * force[p] - springSum(springs, m_perSpring, p);
        dmat3 diagonal(mass[p]);
        for (const std::uint32_t end : springs.incident(p)) {
            const Block& block = m_blocks[end >> 1];
            diagonal += dmat3(block.alpha) + block.beta * glm::outerProduct(block.u, block.u);
        }
        const dmat3 inverse = glm::inverse(diagonal);
        m_inverseDiagonal[p] = Sym3{inverse[0][0], inverse[1][1], inverse[2][2], inverse[1][0], inverse[2][0], inverse[2][1]};
    });
}

void BackwardEuler::springPass(const SpringSystem& springs, const std::vector<dvec3>& w)
{
    forEachIndex(springs.size(), [&](std::size_t s) { m_perSpring[s] = m_blocks[s].apply(w[springs.a(s)] - atB(springs, s, w)); });
}

void BackwardEuler::solve(const SpringSystem& springs, std::span<const double> mass)
{
    // Preconditioned conjugate gradients from the last step's dv: a motion that changes smoothly
    // changes its velocities by nearly as much from one step to the next, and the solve then starts
    // close to its answer. A p is kept by its own recurrence, A p = A z + beta A p_old, so that an
    // iteration is three passes (the springs on z, then two over the bodies) rather than four:
    // each pass on all cores waits for the slowest core at its end.
    const std::size_t n = m_rhs.size();
    if (m_dv.size() != n)
        m_dv.assign(n, dvec3(0.0));
    m_r.resize(n);
    m_z.resize(n);
    m_p.resize(n);
    m_ap.resize(n);
    springPass(springs, m_dv);
    const double scale = sumOf(n, [&](std::size_t p) {
        m_r[p] = m_rhs[p] - (mass[p] * m_dv[p] + springSum(springs, m_perSpring, p));
        return glm::dot(m_rhs[p], m_inverseDiagonal[p].apply(m_rhs[p]));
    });
    double rz = sumOf(n, [&](std::size_t p) {
        m_z[p] = m_inverseDiagonal[p].apply(m_r[p]);
        return glm::dot(m_r[p], m_z[p]);
    });
    m_iterations = 0;
    m_residual = scale > 0.0 ? std::sqrt(std::max(rz, 0.0) / scale) : 0.0;
    // Done when the residual's preconditioned norm is kTolerance of the right-hand side's. (A
    // right-hand side that is not finite stops it at once: the step's check says so.)
    const double target = kTolerance * kTolerance * scale;
    double beta = 0.0;
    while (m_iterations < kMaxIterations && rz > target) {
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
            m_r[p] -= alpha * m_ap[p];
            m_z[p] = m_inverseDiagonal[p].apply(m_r[p]);
            return glm::dot(m_r[p], m_z[p]);
        });
        ++m_iterations;
        beta = next / rz;
        rz = next;
    }
    if (scale > 0.0)
        m_residual = std::sqrt(std::max(rz, 0.0) / scale);
}

} // namespace pba::detail
