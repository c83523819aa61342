// The joints of a mechanism whose bodies are far apart in mass, solved together exactly
// (JointSolver::farApart).
//
// A sweep of a joint between a 50 kg ball and a 0.1 kg link moves the link, not the ball: a pull
// passes down a chain of such links a five-hundredth a sweep, so a heavy ball on light links
// stretched them by a centimetre, came apart at 1/60 s and, on six links, gained energy until the
// step stopped. The rows of every joint together (a small dense system: the blows' rows,
// blowRowsOf, with a hinge's limits as inequalities) are the answer the sweeps converge to,
// whatever the ratio: solved after the velocity sweeps, after the position sweeps (Newton steps on
// the joints' errors at the end poses: anchors apart, a hinge's axes apart, a weld's turn, a
// hinge limit passed) and after RATTLE's projection at the end. Springs stay with the sweeps:
// soft, they pass no pull in an instant.
#include "rigid/joint_solver.hpp"

#include <algorithm>
#include <cmath>
#include <tuple>

#include "rigid/small_lcp.hpp"

namespace pba::rigid {

struct JointSolver::ExactRow {
    enum class Part { Linear, Angular, Axial, Lower, Upper };
    BlowRow row;
    std::uint32_t rows = 0; ///< its joint's place among the solve's rows
    Part part = Part::Linear;
};

namespace {

constexpr double kMet = 1e-9; ///< m/s: a row's speed this close to its target is met

/// blowRowMatrix over rows that hold their BlowRow as `row`, with a ten-billionth of the largest
/// on the diagonal: it picks one of equal answers where rows repeat each other (a loop of joints,
/// a link between two anchors).
template <class Rows>
std::vector<double> rowMatrix(std::span<SolverBody> bodies, const Rows& rows)
{
    const std::size_t n = rows.size();
    std::vector<double> a;
    blowRowMatrix(
        bodies, n, [&](std::size_t i) -> const BlowRow& { return rows[i].row; },
        [&](const BlowRow& row, double lambda) { row.push(bodies[row.a], bodies[row.b], lambda); }, a);
    double largest = 0.0;
    for (std::size_t i = 0; i < n; ++i)
        largest = std::max(largest, a[i * n + i]);
    for (std::size_t i = 0; i < n; ++i)
        a[i * n + i] += 1e-10 * largest;
    return a;
}

} // namespace

std::size_t JointSolver::exactRowsOf(std::span<const Rows> rows, std::vector<ExactRow>& out) const
{
    out.clear();
    std::vector<ExactRow> limitRows;
    std::vector<BlowRow> equalities, limits;
    for (std::uint32_t k = 0; k < rows.size(); ++k) {
        const Rows& r = rows[k];
        const Joint& j = m_joints[r.joint];
        if (j.type == JointType::Distance && j.stiffness > 0.0)
            continue;
        equalities.clear();
        limits.clear();
        blowRowsOf(r, equalities, limits);
        for (const BlowRow& e : equalities) {
            const auto part = j.type == JointType::Distance ? ExactRow::Part::Axial
                              : e.angular                   ? ExactRow::Part::Angular
                                                            : ExactRow::Part::Linear;
            out.push_back({e, k, part});
        }
        if (limits.size() == 2) { // the lower limit's row, then the upper's
            limitRows.push_back({limits[0], k, ExactRow::Part::Lower});
            limitRows.push_back({limits[1], k, ExactRow::Part::Upper});
        }
    }
    const std::size_t equalityCount = out.size();
    out.insert(out.end(), limitRows.begin(), limitRows.end());
    return equalityCount;
}

void JointSolver::solveExactly(std::vector<Rows>& rows)
{
    if (!m_farApart)
        return;
    thread_local std::vector<ExactRow> exact;
    const std::size_t equalities = exactRowsOf(rows, exact);
    const std::size_t n = exact.size();
    if (n == 0 || n > kMaxMechanismRows)
        return;
    // Where the sweeps already met every row (a chain hanging still), there is nothing to do.
    double worst = 0.0;
    for (std::size_t i = 0; i < equalities; ++i)
        worst = std::max(worst, std::abs(exact[i].row.speed(m_bodies[exact[i].row.a], m_bodies[exact[i].row.b]) -
                                         exact[i].row.target));
    if (equalities == n && worst <= kMet)
        return;
    const std::vector<double> a = rowMatrix(m_bodies, exact);
    // In the total impulses x (a limit's at least 0): w = A x + b, b the speed short of the
    // target less what the impulses so far did.
    std::vector<double> current(n, 0.0), b(n), x(n);
    for (std::size_t i = 0; i < n; ++i)
        if (exact[i].part == ExactRow::Part::Lower)
            current[i] = rows[exact[i].rows].lowerImpulse;
        else if (exact[i].part == ExactRow::Part::Upper)
            current[i] = rows[exact[i].rows].upperImpulse;
    double scale = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
        const BlowRow& row = exact[i].row;
        b[i] = row.speed(m_bodies[row.a], m_bodies[row.b]) - row.target;
        for (std::size_t j = equalities; j < n; ++j)
            b[i] -= a[i * n + j] * current[j];
        scale = std::max(scale, std::abs(b[i]));
    }
    if (scale == 0.0)
        return;
    solveSmallLcp(a, b, n, 1e-12 * scale, x, equalities);
    for (std::size_t i = 0; i < n; ++i) {
        const double change = x[i] - current[i];
        exact[i].row.push(m_bodies[exact[i].row.a], m_bodies[exact[i].row.b], change);
        Rows& r = rows[exact[i].rows];
        switch (exact[i].part) {
        case ExactRow::Part::Linear: r.linearImpulse += change * exact[i].row.n; break;
        case ExactRow::Part::Angular: r.angularImpulse += change * exact[i].row.n; break;
        case ExactRow::Part::Axial: r.axialImpulse += change; break;
        case ExactRow::Part::Lower: r.lowerImpulse = x[i]; break;
        case ExactRow::Part::Upper: r.upperImpulse = x[i]; break;
        }
    }
}

struct JointSolver::GapRow {
    BlowRow row;
    double gap = 0.0;
    const Rows* rows = nullptr; ///< its joint's; none for the room's
};

double JointSolver::endErrorRows(std::vector<GapRow>& gaps, std::vector<GapRow>& limits) const
{
    const dvec3 frame[3] = {dvec3(1.0, 0.0, 0.0), dvec3(0.0, 1.0, 0.0), dvec3(0.0, 0.0, 1.0)};
    double widest = 0.0;
    for (const Rows& r : m_rows) {
        const Joint& j = m_joints[r.joint];
        if (j.type == JointType::Distance && j.stiffness > 0.0)
            continue;
        const SolverBody& a = m_bodies[r.a];
        const SolverBody& b = m_bodies[r.b];
        // (A static body's end pose is its start's.)
        const dvec3 ra = glm::mat3_cast(a.endOrientation) * j.localA;
        const dvec3 rb = glm::mat3_cast(b.endOrientation) * j.localB;
        const dvec3 d = (b.endPosition + rb) - (a.endPosition + ra);
        const auto add = [&](std::vector<GapRow>& to, const dvec3& n, bool angular, double gap) {
            to.push_back({{r.a, r.b, ra, rb, n, angular, 0.0}, gap, &r});
            widest = std::max(widest, std::abs(gap));
        };
        if (j.type == JointType::Distance) {
            const double length = glm::length(d);
            if (length > 0.0)
                add(gaps, d / length, false, length - j.length);
            continue;
        }
        for (const dvec3& n : frame)
            add(gaps, n, false, glm::dot(n, d));
        if (j.type == JointType::Fixed) { // B turned from where it should be by -weldError
            const dvec3 theta = weldError(j, a, b);
            for (int k = 0; k < 3; ++k)
                add(gaps, frame[k], true, -theta[k]);
        }
        if (j.type != JointType::Hinge)
            continue;
        const auto [axisA, axisB] = endAxes(j, a, b);
        dvec3 across[2];
        tangentsOf(axisA, across);
        for (const dvec3& n : across) // B's axis is A's turned by about axisA x axisB
            add(gaps, n, true, glm::dot(n, glm::cross(axisA, axisB)));
        if (!j.limited)
            continue;
        const double angle = hingeAngle(j, a.endOrientation, b.endOrientation); // A's relative to B
        if (angle < j.lower)
            add(limits, -axisA, true, angle - j.lower);
        else if (angle > j.upper)
            add(limits, axisA, true, j.upper - angle);
    }
    return widest;
}

double JointSolver::roomRows(const RoomAtEnd& room, std::vector<GapRow>& limits) const
{
    thread_local std::vector<Contact> beyond;
    double deepest = 0.0;
    for (const BodyIndex k : m_movingBodies) {
        beyond.clear();
        room(k, beyond);
        for (const Contact& c : beyond)
            for (int i = 0; i < c.count; ++i) {
                const ContactPoint& p = c.points[i];
                if (p.separation >= 0.0)
                    continue;
                const BlowRow row{k, c.b, p.point - m_bodies[k].endPosition, dvec3(0.0), p.normal, false, 0.0};
                limits.push_back({row, p.separation, nullptr});
                deepest = std::max(deepest, -p.separation);
            }
    }
    return deepest;
}

void JointSolver::holdExactly(const RoomAtEnd& room)
{
    if (!m_farApart)
        return;
    // Newton steps on the joints' errors at the end poses, the hinge limits passed and the points
    // beyond the room (pushing only) among them. Held apart from the room, a light body hinged far
    // from a heavy one was put back on its joint through a wall, and the room's push-out after
    // opened the joint by up to 9 cm.
    thread_local std::vector<GapRow> gaps, limits;
    // The steps' matrix is the start orientations' and a pose turns by a rotation vector's first
    // order, so a light link whipped round in a step converges only linearly: six 0.1 kg links
    // under a 50 kg ball at 1/60 s took up to 33 rounds, two links 7, wrecking-ball 2.
    constexpr int kRounds = 40;
    constexpr double kHeld = 1e-9; // m, and rad
    for (int round = 0; round < kRounds; ++round) {
        gaps.clear();
        limits.clear();
        const double joints = endErrorRows(gaps, limits); // (the room's rows after the joints' limits)
        const double widest = std::max(joints, roomRows(room, limits));
        const std::size_t equalities = gaps.size();
        gaps.insert(gaps.end(), limits.begin(), limits.end());
        const std::size_t n = gaps.size();
        if (n == 0 || n > kMaxMechanismRows || widest <= kHeld)
            return;
        // The pose's change along a row for a move p is the velocity's for an impulse p (movePose).
        const std::vector<double> a = rowMatrix(m_bodies, gaps);
        std::vector<double> b(n), x(n);
        for (std::size_t i = 0; i < n; ++i)
            b[i] = gaps[i].gap;
        solveSmallLcp(a, b, n, 1e-12 * widest, x, equalities);
        moveTogether(gaps, x);
    }
}

template <class GapRows>
void JointSolver::moveTogether(const GapRows& rows, std::span<const double> x)
{
    // Each body's moves summed before it turns: the rows' pushes on a light body nearly cancel,
    // and turned one after another by their rotation vectors, each right to first order only,
    // they did not (a light frame between a heavy door's hinge and the world turned 17 rad and
    // back, and the anchors came apart).
    struct Move {
        dvec3 p{0.0}, l{0.0}, pRattle{0.0}, lRattle{0.0};
    };
    thread_local std::vector<Move> moves;
    moves.assign(m_movingBodies.size(), Move{});
    const auto moveOf = [&](BodyIndex k) -> Move* {
        const auto at = std::lower_bound(m_movingBodies.begin(), m_movingBodies.end(), k);
        return at != m_movingBodies.end() && *at == k ? &moves[std::size_t(at - m_movingBodies.begin())] : nullptr;
    };
    for (std::size_t i = 0; i < rows.size(); ++i) {
        const BlowRow& row = rows[i].row;
        const bool rattle = rows[i].rows && rows[i].rows->rattle;
        for (const auto& [k, sign, arm] : {std::tuple(row.a, -1.0, row.rA), std::tuple(row.b, 1.0, row.rB)}) {
            Move* m = moveOf(k);
            if (!m)
                continue;
            const dvec3 p = row.angular ? dvec3(0.0) : sign * x[i] * row.n;
            const dvec3 l = row.angular ? sign * x[i] * row.n : glm::cross(arm, p);
            m->p += p;
            m->l += l;
            if (rattle) {
                m->pRattle += p;
                m->lRattle += l;
            }
        }
    }
    for (std::size_t k = 0; k < moves.size(); ++k) {
        SolverBody& body = m_bodies[m_movingBodies[k]];
        const Move& m = moves[k];
        body.endPosition += body.inverseMass * m.p;
        body.endOrientation = turned(body.endOrientation, body.inverseInertia * m.l);
        // RATTLE's pose drifts by its half-step velocity, which carries on into the end velocity
        // (move's reason).
        body.v += body.inverseMass * m.pRattle / m_settings.dt;
        body.w += body.inverseInertia * m.lRattle / m_settings.dt;
    }
}

} // namespace pba::rigid
