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
    // Each row's two bodies, and the sign an impulse along the row has on each.
    struct End {
        BodyIndex body;
        double sign;
    };
    const std::size_t n = m_velocityRows.size();
    std::vector<End> ends(2 * n);
    for (const IslandContact& c : m_constraints)
        for (int p = 0; p < c.count; ++p) {
            const std::size_t i = c.first + std::size_t(p);
            ends[2 * i] = {c.a, -1.0};
            ends[2 * i + 1] = {c.b, 1.0};
        }
    // A = J M^-1 J^T: rows i and j meet on the bodies they share (a static body moves for none).
    std::vector<double>& a = m_exactMatrix;
    a.assign(n * n, 0.0);
    for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = 0; j < n; ++j)
            for (int si = 0; si < 2; ++si)
                for (int sj = 0; sj < 2; ++sj) {
                    const End& ei = ends[2 * i + std::size_t(si)];
                    const End& ej = ends[2 * j + std::size_t(sj)];
                    const SolverBody& body = m_bodies[ei.body];
                    if (ei.body != ej.body || body.isStatic())
                        continue;
                    const Jacobian& ri = m_velocityRows[i].along;
                    const Jacobian& rj = m_velocityRows[j].along;
                    const dvec3 momentI(si == 0 ? ri.momentA : ri.momentB), turnJ(sj == 0 ? rj.turnA : rj.turnB);
                    a[i * n + j] += ei.sign * ej.sign *
                                    (body.inverseMass * glm::dot(dvec3(ri.u), dvec3(rj.u)) + glm::dot(momentI, turnJ));
                }
    std::vector<double> b(n), x(n);
    for (int round = 0; round < kExactRounds; ++round) {
        double scale = 0.0;
        for (std::size_t i = 0; i < n; ++i) {
            const VelocityRows& r = m_velocityRows[i];
            b[i] = speedAlong(r.along, m_bodies[ends[2 * i].body], m_bodies[ends[2 * i + 1].body]) - r.target;
            for (std::size_t j = 0; j < n; ++j)
                b[i] -= a[i * n + j] * m_velocityRows[j].normalImpulse;
            scale = std::max(scale, std::abs(b[i]));
        }
        solveSmallLcp(a, b, n, 1e-12 * scale, x);
        for (std::size_t i = 0; i < n; ++i) {
            VelocityRows& r = m_velocityRows[i];
            applyAlong(r.along, x[i] - r.normalImpulse, m_bodies[ends[2 * i].body], m_bodies[ends[2 * i + 1].body]);
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
