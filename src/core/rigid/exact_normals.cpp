// The end of pass 2 of the contact solver (contact_solver.hpp) for a small island where a body
// touches one far lighter: its normal impulses solved exactly, as one small LCP.
//
// A sweep passes a push between two bodies at a rate set by their masses: under a 50 kg box a
// 0.1 kg one takes back 1/500 of the press a sweep, so a tower of such boxes in turn fell apart
// long before the sweeps agreed. The LCP over every normal row of the island (w = A x + b, each
// row's speed at least its target, its impulse at least 0, one of them at its bound) is the
// answer the sweeps converge to, with the bodies' own masses, whatever their ratio. Friction,
// whose bounds the normal impulses set, takes a sweep between two such solves.
#include "rigid/contact_solver.hpp"

#include <algorithm>
#include <cmath>

#include "rigid/small_lcp.hpp"

namespace pba::rigid {

bool ContactSolver::needsExactNormals() const
{
    if (m_velocityRows.size() > kMostExactRows)
        return false;
    for (const IslandContact& c : m_constraints)
        if (farLighterIn(c, c.a) || farLighterIn(c, c.b))
            return true;
    return false;
}

void ContactSolver::solveNormalsExactly()
{
    // So few contacts are swept one at a time: their impulses are the rows' own, none packed.
    static_assert(kMostExactRows < WideContactRows::kFewest);
    // Each row's two bodies.
    const std::size_t n = m_velocityRows.size();
    std::vector<std::pair<BodyIndex, BodyIndex>> ends(n);
    for (const IslandContact& c : m_constraints)
        for (int p = 0; p < c.count; ++p)
            ends[c.first + std::size_t(p)] = {c.a, c.b};
    const auto speed = [&](std::size_t i) {
        return speedAlong(m_velocityRows[i].along, m_bodies[ends[i].first], m_bodies[ends[i].second]);
    };
    // A = J M^-1 J^T: row i's change of speed for a unit impulse along row j, found by pushing
    // and putting back (as the blows' matrix is).
    std::vector<double>& a = m_exactMatrix;
    a.resize(n * n);
    std::vector<double> now(n);
    for (std::size_t i = 0; i < n; ++i)
        now[i] = speed(i);
    for (std::size_t j = 0; j < n; ++j) {
        SolverBody& pa = m_bodies[ends[j].first];
        SolverBody& pb = m_bodies[ends[j].second];
        const SolverBody keptA = pa, keptB = pb;
        applyAlong(m_velocityRows[j].along, 1.0, pa, pb);
        for (std::size_t i = 0; i < n; ++i)
            a[i * n + j] = speed(i) - now[i];
        pa = keptA;
        pb = keptB;
    }
    std::vector<double> b(n), x(n);
    for (int round = 0; round < kExactRounds; ++round) {
        double scale = 0.0;
        for (std::size_t i = 0; i < n; ++i) {
            const VelocityRows& r = m_velocityRows[i];
            b[i] = speed(i) - r.target;
            for (std::size_t j = 0; j < n; ++j)
                b[i] -= a[i * n + j] * m_velocityRows[j].normalImpulse;
            scale = std::max(scale, std::abs(b[i]));
        }
        solveSmallLcp(a, b, n, 1e-12 * scale, x);
        for (std::size_t i = 0; i < n; ++i) {
            VelocityRows& r = m_velocityRows[i];
            applyAlong(r.along, x[i] - r.normalImpulse, m_bodies[ends[i].first], m_bodies[ends[i].second]);
            r.normalImpulse = x[i];
        }
        if (round + 1 == kExactRounds)
            break;
        double change = 0.0;
        for (const IslandContact& c : m_constraints)
            solveFriction(c, m_bodies[c.a], m_bodies[c.b], change);
    }
}

} // namespace pba::rigid
