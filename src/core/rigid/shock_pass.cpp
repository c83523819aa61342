// The end of pass 2 of the contact solver (contact_solver.hpp) for an island where a body rests
// on one far lighter: shock propagation (Guendelman, Bridson and Fedkiw 2003), on velocities.
//
// Sweeps pass a push between two bodies at a rate set by their masses: between a 50 kg box and
// the 0.1 kg cube it stands on, each sweep takes back only 1/500 of what the box presses in, so
// the cube is squeezed out sideways long before they agree. Here the bodies are ranked by how many
// contacts lie between them and the room or a fixed body, and the contacts are swept rank by rank
// from the bottom, each body of a lower rank held as if fixed: the cube stops on the floor, then
// the box stops on the cube. The impulses this finds are what the next step's warm start begins
// from, and from them the ordinary sweeps hold the stack.
#include "rigid/contact_solver.hpp"

#include <algorithm>
#include <limits>

namespace pba::rigid {

bool ContactSolver::needsShock() const
{
    for (const IslandContact& c : m_constraints) {
        const double wa = m_bodies[c.a].inverseMass, wb = m_bodies[c.b].inverseMass;
        if (wa > 0.0 && wb > 0.0 && std::max(wa, wb) > kShockRatio * std::min(wa, wb))
            return true;
    }
    return false;
}

void ContactSolver::rankFromTheGround()
{
    constexpr int kUnranked = std::numeric_limits<int>::max();
    if (m_rank.size() < m_bodies.size())
        m_rank.resize(m_bodies.size());
    for (const std::uint32_t k : m_moving)
        m_rank[k] = kUnranked;
    const auto rank = [&](BodyIndex k) { return m_bodies[k].isStatic() ? 0 : m_rank[k]; };
    // A body's rank is one more than its lowest partner's; the island is small (no halves).
    for (bool changed = true; changed;) {
        changed = false;
        for (const IslandContact& c : m_constraints) {
            const int ra = rank(c.a), rb = rank(c.b);
            if (ra != kUnranked && ra + 1 < rb) {
                m_rank[c.b] = ra + 1;
                changed = true;
            } else if (rb != kUnranked && rb + 1 < ra) {
                m_rank[c.a] = rb + 1;
                changed = true;
            }
        }
    }
}

void ContactSolver::propagateShock()
{
    rankFromTheGround();
    m_wide.storeImpulses(m_velocityRows);
    // The contacts by the rank of their higher body, in the island's order within a rank; those
    // of bodies no contact joins to the ground (a cluster in the air) are left out.
    const auto rank = [&](BodyIndex k) { return m_bodies[k].isStatic() ? 0 : m_rank[k]; };
    m_byRank.clear();
    for (std::uint32_t k = 0; k < m_constraints.size(); ++k)
        if (const int r = std::max(rank(m_constraints[k].a), rank(m_constraints[k].b));
            r != std::numeric_limits<int>::max())
            m_byRank.emplace_back(r, k);
    std::stable_sort(m_byRank.begin(), m_byRank.end(), [](const auto& p, const auto& q) { return p.first < q.first; });
    for (std::size_t first = 0; first < m_byRank.size();) {
        const int level = m_byRank[first].first;
        std::size_t last = first;
        while (last < m_byRank.size() && m_byRank[last].first == level)
            ++last;
        for (int sweep = 0; sweep < kShockSweeps; ++sweep) {
            double change = 0.0, largest = 0.0;
            for (std::size_t i = first; i < last; ++i) {
                const IslandContact& c = m_constraints[m_byRank[i].second];
                const Held held{rank(c.a) < level, rank(c.b) < level};
                solveFriction(c, m_bodies[c.a], m_bodies[c.b], change, held);
                solveNormal(c, m_bodies[c.a], m_bodies[c.b], change, largest, held);
            }
            if (change <= kShockConverged * largest)
                break;
        }
        first = last;
    }
    m_wide.loadImpulses(m_velocityRows);
}

} // namespace pba::rigid
