// The end of pass 2 of the contact solver (contact_solver.hpp) for an island where a body touches
// one far lighter: its normal impulses solved exactly, as one quadratic program.
//
// A sweep passes a push between two bodies at a rate set by their masses: under a 50 kg box a
// 0.1 kg one takes back 1/500 of the press a sweep, so a tower of such boxes in turn fell apart
// long before the sweeps agreed. The LCP over every normal row of the island (w = A x + b, each
// row's speed at least its target, its impulse at least 0, one of them at its bound) is the
// answer the sweeps converge to, with the bodies' own masses, whatever their ratio. It is the
// minimum of a convex quadratic over x >= 0 (bounded_qp.hpp), solved from the sweeps' impulses
// with the matrix applied row by row, never formed: a bed of dice under a slab is hundreds of
// rows. Friction, whose bounds the normal impulses set, takes a sweep between two such solves;
// in a mechanism the joints take theirs there too (their rows stay with the sweeps).
#include "rigid/contact_solver.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "rigid/bounded_qp.hpp"
#include "rigid/joint_solver.hpp"

namespace pba::rigid {

bool ContactSolver::needsExactNormals() const
{
    for (const IslandContact& c : m_constraints)
        if (farLighterIn(c, c.a) || farLighterIn(c, c.b))
            return true;
    return false;
}

namespace {

/// One normal row in double, its bodies by their place among the island's moving ones (-1: static).
struct ExactRow {
    dvec3 u{0.0}, momentA{0.0}, momentB{0.0}, turnA{0.0}, turnB{0.0};
    double inverseMassA = 0.0, inverseMassB = 0.0;
    std::int32_t a = -1, b = -1;
    double scale = 1.0; ///< sqrt of the row's effective mass: the program's rows all of unit diagonal
};

/// A x for the scaled rows: the impulses along the rows into per-body velocity changes, read back
/// as the rows' speeds.
class ExactProduct {
public:
    ExactProduct(std::span<const ExactRow> rows, std::size_t bodies) : m_rows(rows), m_dv(bodies), m_dw(bodies) {}

    void operator()(std::span<const double> in, std::span<double> out)
    {
        std::fill(m_dv.begin(), m_dv.end(), dvec3(0.0));
        std::fill(m_dw.begin(), m_dw.end(), dvec3(0.0));
        for (std::size_t j = 0; j < m_rows.size(); ++j) {
            const ExactRow& r = m_rows[j];
            const double lambda = in[j] * r.scale;
            if (r.a >= 0) {
                m_dv[std::size_t(r.a)] -= (lambda * r.inverseMassA) * r.u;
                m_dw[std::size_t(r.a)] -= lambda * r.turnA;
            }
            if (r.b >= 0) {
                m_dv[std::size_t(r.b)] += (lambda * r.inverseMassB) * r.u;
                m_dw[std::size_t(r.b)] += lambda * r.turnB;
            }
        }
        for (std::size_t i = 0; i < m_rows.size(); ++i) {
            const ExactRow& r = m_rows[i];
            double speed = 0.0;
            if (r.a >= 0)
                speed -= glm::dot(r.u, m_dv[std::size_t(r.a)]) + glm::dot(r.momentA, m_dw[std::size_t(r.a)]);
            if (r.b >= 0)
                speed += glm::dot(r.u, m_dv[std::size_t(r.b)]) + glm::dot(r.momentB, m_dw[std::size_t(r.b)]);
            // A face's four points on a body that turns three ways are one row too many: a
            // ten-billionth on the diagonal picks one of the equal answers.
            out[i] = r.scale * speed + 1e-10 * in[i];
        }
    }

private:
    std::span<const ExactRow> m_rows;
    std::vector<dvec3> m_dv, m_dw;
};

/// Each normal row of the island in double, its moving bodies numbered from 0 for the product.
struct ExactRows {
    std::vector<ExactRow> rows;
    std::vector<std::pair<BodyIndex, BodyIndex>> ends; ///< each row's bodies, the solver's indices
    std::size_t bodies = 0;
};

/// `place` holds -1 for every body on entry and on return (a scratch of the solver's).
ExactRows exactRows(std::span<const IslandContact> contacts, std::span<const VelocityRows> velocityRows,
                    std::span<const SolverBody> bodies, std::vector<std::int32_t>& place)
{
    if (place.size() < bodies.size())
        place.resize(bodies.size(), -1);
    std::vector<BodyIndex> placed;
    const auto placeOf = [&](BodyIndex k) {
        if (bodies[k].isStatic())
            return std::int32_t(-1);
        if (place[k] < 0) {
            place[k] = std::int32_t(placed.size());
            placed.push_back(k);
        }
        return place[k];
    };
    ExactRows exact;
    exact.rows.resize(velocityRows.size());
    exact.ends.resize(velocityRows.size());
    for (const IslandContact& c : contacts)
        for (int p = 0; p < c.count; ++p) {
            const std::size_t i = c.first + std::size_t(p);
            const Jacobian& j = velocityRows[i].along;
            exact.rows[i] = {dvec3(j.u), dvec3(j.momentA), dvec3(j.momentB), dvec3(j.turnA), dvec3(j.turnB),
                             bodies[c.a].inverseMass, bodies[c.b].inverseMass, placeOf(c.a), placeOf(c.b),
                             std::sqrt(double(j.mass))};
            exact.ends[i] = {c.a, c.b};
        }
    exact.bodies = placed.size();
    for (const BodyIndex k : placed)
        place[k] = -1;
    return exact;
}

} // namespace

void ContactSolver::finishVelocities(JointSolver* joints)
{
    if (needsExactNormals())
        solveNormalsExactly(joints);
}

void ContactSolver::solveNormalsExactly(JointSolver* joints)
{
    // A large island's sweeps keep their impulses in their blocks (a halved one's, each part's):
    // here the rows' are the truth.
    const auto eachWide = [&](auto&& use) {
        if (m_halved)
            for (Part& p : m_parts)
                use(p.wide);
        else
            use(m_wide);
    };
    eachWide([&](WideContactRows& wide) { wide.storeImpulses(m_velocityRows); });
    const ExactRows exact = exactRows(m_constraints, m_velocityRows, m_bodies, m_exactPlace);
    const std::size_t n = exact.rows.size();
    ExactProduct product(exact.rows, exact.bodies);
    const QpProduct multiply = [&](std::span<const double> in, std::span<double> out) { product(in, out); };
    const double eigenvalue = 1.1 * largestEigenvalue(multiply, n);
    // Solved when no row's speed is off by more than kExactSpeed on average (the program's rows
    // are speeds times the root of their masses).
    double massSum = 0.0;
    for (const ExactRow& r : exact.rows)
        massSum += r.scale * r.scale;
    const double tolerance = kExactSpeed * std::sqrt(massSum);
    // The program is in the change of each impulse from what it is, scaled to unit diagonal:
    // x = x_now + scale y >= 0, and c is each row's speed short of its target.
    std::vector<double> c(n), lower(n), y(n);
    const std::vector<double> upper(n, std::numeric_limits<double>::infinity());
    for (int round = 0; round < kExactRounds; ++round) {
        for (std::size_t i = 0; i < n; ++i) {
            const VelocityRows& r = m_velocityRows[i];
            const auto [a, b] = exact.ends[i];
            c[i] = exact.rows[i].scale * (speedAlong(r.along, m_bodies[a], m_bodies[b]) - r.target);
            lower[i] = -r.normalImpulse / exact.rows[i].scale;
        }
        std::fill(y.begin(), y.end(), 0.0);
        solveBoundedQp(multiply, c, lower, upper, eigenvalue, tolerance, kExactIterations, y);
        for (std::size_t i = 0; i < n; ++i) {
            VelocityRows& r = m_velocityRows[i];
            const auto [a, b] = exact.ends[i];
            const double next = std::max(r.normalImpulse + exact.rows[i].scale * y[i], 0.0);
            applyAlong(r.along, next - r.normalImpulse, m_bodies[a], m_bodies[b]);
            r.normalImpulse = next;
        }
        if (round + 1 == kExactRounds)
            break;
        double change = 0.0;
        for (const IslandContact& contact : m_constraints)
            solveFriction(contact, m_bodies[contact.a], m_bodies[contact.b], change);
        if (joints)
            joints->solveVelocities();
    }
    eachWide([&](WideContactRows& wide) { wide.loadImpulses(m_velocityRows); });
}

} // namespace pba::rigid
