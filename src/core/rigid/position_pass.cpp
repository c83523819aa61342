// Pass 3 of the contact solver (contact_solver.hpp): what still overlaps at the end poses is
// pushed apart on the poses alone, a point at a time, adding no motion.
#include "rigid/contact_solver.hpp"

#include <algorithm>

namespace pba::rigid {

void ContactSolver::positionRows(std::span<const Contact> contacts)
{
    // A halved island's part by part, each part's in its contacts' order.
    const auto halfOfContact = [&](const Contact& c) {
        if (!m_halved)
            return std::size_t(0);
        const auto side = [&](BodyIndex k) { return k < m_side.size() ? int(m_side[k]) : -1; };
        return std::size_t(halfOf(side(c.a), side(c.b)));
    };
    std::fill(std::begin(m_partRows), std::end(m_partRows), std::size_t(0));
    for (const Contact& c : contacts)
        m_partRows[halfOfContact(c) + 1] += std::size_t(c.count);
    for (std::size_t h = 0; h < 3; ++h)
        m_partRows[h + 1] += m_partRows[h];
    m_positionRows.resize(m_partRows[3]);
    m_positionRowsBuilt = true;
    std::size_t fill[3] = {m_partRows[0], m_partRows[1], m_partRows[2]};
    for (const Contact& c : contacts) {
        const SolverBody& a = m_bodies[c.a];
        const SolverBody& b = m_bodies[c.b];
        const dmat3 ra = glm::mat3_cast(a.endOrientation), rb = glm::mat3_cast(b.endOrientation);
        std::size_t& next = fill[halfOfContact(c)];
        for (int i = 0; i < c.count; ++i) {
            const ContactPoint& p = c.points[i];
            m_positionRows[next++] = {c.a, c.b, p.normal, c.radiusA, c.radiusB, ra * p.anchorA, rb * p.anchorB};
        }
    }
}

void ContactSolver::solvePositions(std::span<const Contact> contacts)
{
    positionRows(contacts); // the joints' sweeps turn the bodies between the contacts'
    for (const PositionRow& row : m_positionRows)
        solvePosition(row);
}

void ContactSolver::solvePositions(std::span<const Contact> contacts, int sweeps)
{
    // Without joints nothing turns a body in this pass: each point's arms are turned once, and a
    // sweep only adds them to the moving centres.
    positionRows(contacts);
    const auto sweep = [&](std::size_t h) {
        for (std::size_t r = m_partRows[h]; r < m_partRows[h + 1]; ++r)
            solvePosition(m_positionRows[r]);
    };
    if (!m_halved) {
        for (int it = 0; it < sweeps; ++it)
            sweep(0);
        return;
    }
    runHalves(sweeps, [&](int, Half half) {
        sweep(std::size_t(half));
        return true;
    });
}

void ContactSolver::settleOn(std::span<const Contact> contacts, std::span<const std::uint32_t> held, int sweeps)
{
    // A die on the floor pressed into the one above it: the sweeps share each push between the
    // two, and the floor pushes the lower one back up, so some overlap is left; the push-out then
    // lifts it the rest of the way into the die above. Held as the room is, it stays, and the die
    // above takes the whole push (shock propagation, one layer). The push-out turned nothing, so
    // the last sweeps' rows still hold.
    if (!m_positionRowsBuilt)
        positionRows(contacts);
    if (m_held.size() < m_bodies.size())
        m_held.resize(m_bodies.size(), 0);
    for (const std::uint32_t k : held)
        m_held[k] = 1;
    for (int it = 0; it < sweeps; ++it)
        for (const PositionRow& row : m_positionRows)
            pushApart(row, m_held[row.a] ? 0.0 : m_bodies[row.a].inverseMass,
                      m_held[row.b] ? 0.0 : m_bodies[row.b].inverseMass);
    for (const std::uint32_t k : held) // left all clear for the next island's
        m_held[k] = 0;
}

void ContactSolver::pushApart(const PositionRow& row, double wa, double wb)
{
    const double k = wa + wb;
    if (k == 0.0)
        return;
    SolverBody& a = m_bodies[row.a];
    SolverBody& b = m_bodies[row.b];
    // The normal is held as it was found (as Box2D holds it through its substeps), but for two
    // spheres: the bodies turn little within a sweep. The surface points as surfacePoints has them.
    dvec3 n = row.n;
    if (row.radiusA > 0.0 && row.radiusB > 0.0) {
        const dvec3 d = b.endPosition - a.endPosition;
        if (const double len = glm::length(d); len > 0.0)
            n = d / len;
    }
    const dvec3 pa = row.radiusA > 0.0 ? a.endPosition + row.radiusA * n : a.endPosition + row.armA;
    const dvec3 pb = row.radiusB > 0.0 ? b.endPosition - row.radiusB * n : b.endPosition + row.armB;
    const SolverSettings& s = m_settings;
    const double separation = glm::dot(pb - pa, n);
    const double correction = std::clamp(s.contact.baumgarte * (separation + s.contact.linearSlop), -s.maxCorrection, 0.0);
    if (correction == 0.0)
        return;
    // Apart along the normal, without turning: a turn about one point of a manifold (an edge
    // crossing an edge has only one) digs another corner in, which this manifold, found before
    // the sweeps, does not hold.
    const dvec3 push = (-correction / k) * n;
    if (wa != 0.0)
        a.endPosition -= push * wa;
    if (wb != 0.0)
        b.endPosition += push * wb;
}

} // namespace pba::rigid
