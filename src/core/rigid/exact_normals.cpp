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
// in a mechanism the joints take theirs there too (and, where a joint joins bodies far apart in
// mass, their own exact solve: exact_joints.cpp).
#include "rigid/contact_solver.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>
#include <utility>
#include <vector>

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

/// One normal row of the program: its bodies by their place among the island's moving ones (the
/// static ones share the last place, never written).
struct ExactRow {
    const Jacobian* along = nullptr;
    std::uint32_t a = 0, b = 0;
    double scale = 1.0; ///< sqrt of the row's effective mass: the program's rows all of unit diagonal
};

/// What the impulses of one product do to a body: its velocities' change, by the sweeps' own
/// formulas (speedAlong, applyAlong).
struct VelocityChange {
    dvec3 v{0.0}, w{0.0};
    double inverseMass = 0.0;
    bool isStatic() const { return inverseMass == 0.0; }
};

/// A x for the scaled rows: the impulses along the rows into per-body velocity changes, read back
/// as the rows' speeds.
class ExactProduct {
public:
    ExactProduct(std::span<const ExactRow> rows, std::vector<VelocityChange> bodies)
        : m_rows(rows), m_bodies(std::move(bodies))
    {
    }

    void operator()(std::span<const double> in, std::span<double> out)
    {
        for (VelocityChange& body : m_bodies)
            body.v = body.w = dvec3(0.0);
        for (std::size_t j = 0; j < m_rows.size(); ++j) {
            const ExactRow& r = m_rows[j];
            applyAlong(*r.along, in[j] * r.scale, m_bodies[r.a], m_bodies[r.b]);
        }
        for (std::size_t i = 0; i < m_rows.size(); ++i) {
            const ExactRow& r = m_rows[i];
            // A face's four points on a body that turns three ways are one row too many: a
            // ten-billionth on the diagonal picks one of the equal answers.
            out[i] = r.scale * speedAlong(*r.along, m_bodies[r.a], m_bodies[r.b]) + 1e-10 * in[i];
        }
    }

private:
    std::span<const ExactRow> m_rows;
    std::vector<VelocityChange> m_bodies;
};

/// Each normal row of the island, its moving bodies numbered from 0 for the product.
struct ExactRows {
    std::vector<ExactRow> rows;
    std::vector<std::pair<BodyIndex, BodyIndex>> ends; ///< each row's bodies, the solver's indices
    std::vector<VelocityChange> bodies;                ///< the moving ones, then one static
};

/// `place` holds -1 for every body on entry and on return (a scratch of the solver's).
ExactRows exactRows(std::span<const IslandContact> contacts, std::span<const VelocityRows> velocityRows,
                    std::span<const SolverBody> bodies, std::vector<std::int32_t>& place)
{
    if (place.size() < bodies.size())
        place.resize(bodies.size(), -1);
    std::vector<BodyIndex> placed;
    for (const IslandContact& c : contacts)
        for (const BodyIndex k : {c.a, c.b})
            if (!bodies[k].isStatic() && place[k] < 0) {
                place[k] = std::int32_t(placed.size());
                placed.push_back(k);
            }
    const auto placeOf = [&](BodyIndex k) {
        return bodies[k].isStatic() ? std::uint32_t(placed.size()) : std::uint32_t(place[k]);
    };
    ExactRows exact;
    exact.rows.resize(velocityRows.size());
    exact.ends.resize(velocityRows.size());
    for (const IslandContact& c : contacts)
        for (int p = 0; p < c.count; ++p) {
            const std::size_t i = c.first + std::size_t(p);
            const Jacobian& j = velocityRows[i].along;
            exact.rows[i] = {&j, placeOf(c.a), placeOf(c.b), std::sqrt(double(j.mass))};
            exact.ends[i] = {c.a, c.b};
        }
    exact.bodies.resize(placed.size() + 1);
    for (std::size_t k = 0; k < placed.size(); ++k)
        exact.bodies[k].inverseMass = bodies[placed[k]].inverseMass;
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
    ExactRows exact = exactRows(m_constraints, m_velocityRows, m_bodies, m_exactPlace);
    const std::size_t n = exact.rows.size();
    ExactProduct product(exact.rows, std::move(exact.bodies));
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
        if (joints) {
            joints->solveVelocities();
            joints->solveVelocitiesExactly();
        }
    }
    eachWide([&](WideContactRows& wide) { wide.loadImpulses(m_velocityRows); });
}

} // namespace pba::rigid
