// Pass 1 of the contact solver (contact_solver.hpp): restitution at the time of arrival. Each
// contact whose points arrive faster than a resting speed takes, at that time and those points,
// the impulses that send them off at e times their arriving speed.
#include "rigid/contact_solver.hpp"
#include "rigid/joint_solver.hpp"
#include "rigid/small_lcp.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>

namespace pba::rigid {

namespace {

/// The smallest s in [0, span] at which gap + u s + a s^2 / 2 reaches 0, or NaN if it does not
/// within the span. A gap already closed is reached at once.
double arrival(double gap, double u, double a, double span)
{
    if (gap <= 0.0)
        return 0.0;
    constexpr double nan = std::numeric_limits<double>::quiet_NaN();
    if (a == 0.0)
        return u < 0.0 && -gap / u <= span ? -gap / u : nan;
    const double disc = u * u - 2.0 * a * gap;
    if (disc < 0.0)
        return nan;
    // The smaller positive root of a s^2 / 2 + u s + gap, in the form that does not cancel.
    const double q = -(u + std::copysign(std::sqrt(disc), u));
    double s1 = q / a, s2 = q != 0.0 ? 2.0 * gap / q : nan;
    double s = std::numeric_limits<double>::infinity();
    for (double root : {s1, s2})
        if (root >= 0.0 && root < s)
            s = root;
    return s <= span ? s : nan;
}

constexpr int kMaxPoints = contact::Manifold::kMaxPoints;
constexpr int kMaxImpactSweeps = 32;

} // namespace

void ContactSolver::startCollisions()
{
    // A contact that found no arrival finds none again until one of its bodies is struck: each
    // body counts its blows, and a contact is looked at again only when the counts it last saw
    // have changed (the sweeps' results are those of looking at every contact every sweep).
    if (m_blows.size() < m_bodies.size())
        m_blows.resize(m_bodies.size());
    for (const IslandContact& c : m_constraints)
        m_blows[c.a] = m_blows[c.b] = 0;
    m_seen.assign(m_constraints.size(), ~std::uint64_t(0));
    m_strikes.assign(m_constraints.size(), 0);
}

bool ContactSolver::collide(int maxStrikes)
{
    startCollisions();
    bool any = false;
    for (int sweep = 0; sweep < kMaxCollisionSweeps; ++sweep) {
        bool changed = false;
        for (std::size_t k = 0; k < m_constraints.size(); ++k)
            changed = lookForBlow(k, maxStrikes) || changed;
        if (!changed)
            break;
        any = true;
    }
    markVelocities(m_moving);
    return any;
}

bool ContactSolver::collide(JointSolver& joints)
{
    m_impactJoints = &joints;
    joints.beginBlows();
    m_pins = joints.pins();
    if (m_pinOf.size() < m_bodies.size())
        m_pinOf.resize(m_bodies.size(), -1);
    for (std::size_t i = 0; i < m_pins.size(); ++i)
        m_pinOf[m_pins[i].body] = std::int32_t(i);
    const bool any = collide(kEveryStrike);
    for (const Pin& pin : m_pins)
        m_pinOf[pin.body] = -1;
    m_pins = {};
    joints.endBlows();
    m_impactJoints = nullptr;
    return any;
}

double ContactSolver::blowInverseMass(BodyIndex k, const dvec3& r, const dvec3& u) const
{
    if (!m_pins.empty() && m_pinOf[k] >= 0)
        return m_pins[std::size_t(m_pinOf[k])].inverseMassAlong(r, u);
    const SolverBody& body = m_bodies[k];
    const dvec3 c = glm::cross(r, u);
    return body.inverseMass + glm::dot(c, body.inverseInertia * c);
}

double ContactSolver::blowMass(BodyIndex a, BodyIndex b, const dvec3& ra, const dvec3& rb, const dvec3& u) const
{
    const bool pinned = !m_pins.empty() && (m_pinOf[a] >= 0 || m_pinOf[b] >= 0);
    // 1 / (1/mA + 1/mB + (rA x u) . IA^-1 (rA x u) + (rB x u) . IB^-1 (rB x u)), summed in this
    // order for free bodies; 0 between two static bodies.
    const SolverBody& x = m_bodies[a];
    const SolverBody& y = m_bodies[b];
    const dvec3 ca = glm::cross(ra, u), cb = glm::cross(rb, u);
    const double k = pinned ? blowInverseMass(a, ra, u) + blowInverseMass(b, rb, u)
                            : x.inverseMass + y.inverseMass + glm::dot(ca, x.inverseInertia * ca) +
                                  glm::dot(cb, y.inverseInertia * cb);
    return k > 0.0 ? 1.0 / k : 0.0;
}

void ContactSolver::applyBlow(BodyIndex a, BodyIndex b, const dvec3& rA, const dvec3& rB, const dvec3& p)
{
    for (const auto& [k, impulse, arm] : {std::tuple(a, -p, rA), std::tuple(b, p, rB)}) {
        SolverBody& body = m_bodies[k];
        if (body.isStatic())
            continue;
        if (!m_pins.empty() && m_pinOf[k] >= 0)
            m_pins[std::size_t(m_pinOf[k])].applyImpulse(body, impulse, arm);
        else
            body.applyImpulse(impulse, arm);
    }
}

void ContactSolver::pushRow(const BlowRow& r, double lambda)
{
    if (r.angular) // a mechanism's body: never pinned
        return r.push(m_bodies[r.a], m_bodies[r.b], lambda);
    applyBlow(r.a, r.b, r.rA, r.rB, lambda * r.n);
}

bool ContactSolver::farLighterIn(const IslandContact& c, BodyIndex k) const
{
    const BodyIndex other = k == c.a ? c.b : c.a;
    const double wk = m_bodies[k].inverseMass, wOther = m_bodies[other].inverseMass;
    return wOther > 0.0 && wk > kFarLighter * wOther;
}

void ContactSolver::restingRows(const IslandContact& c, std::span<const ImpactRow> rows)
{
    m_resting.clear();
    const auto held = [&](BodyIndex k) {
        return (!m_pins.empty() && m_pinOf[k] >= 0 && (k == c.a || k == c.b)) || farLighterIn(c, k) ||
               std::find(m_mechanism.begin(), m_mechanism.end(), k) != m_mechanism.end();
    };
    for (const IslandContact& other : m_constraints) {
        const bool heldA = held(other.a) && m_bodies[other.b].isStatic();
        const bool heldB = held(other.b) && m_bodies[other.a].isStatic();
        if (!heldA && !heldB)
            continue;
        for (int i = 0; i < other.count; ++i) {
            const bool struck = &other == &c && std::any_of(rows.begin(), rows.end(), [&](const ImpactRow& row) {
                return row.point == i;
            });
            const PointRows& r = m_rows[other.first + i];
            if (struck || r.separation > m_settings.contact.linearSlop)
                continue;
            RestingRow row{other.a, other.b, r};
            row.rows.normalMass = blowMass(other.a, other.b, r.rA, r.rB, r.n);
            row.targetN = std::min(glm::dot(r.n, relativeVelocity(m_bodies[other.a], m_bodies[other.b], r)), 0.0);
            m_resting.push_back(row);
        }
    }
    // The blow's LCP is dense (its cost the cube of its rows, each sweep): a board on a hundred
    // posts keeps the points closest to touching.
    if (m_resting.size() > kMaxRestingRows) {
        std::nth_element(m_resting.begin(), m_resting.begin() + kMaxRestingRows, m_resting.end(),
                         [](const RestingRow& x, const RestingRow& y) { return x.rows.separation < y.rows.separation; });
        m_resting.resize(kMaxRestingRows);
    }
}

void ContactSolver::solveBlowNormals(const IslandContact& c, std::span<ImpactRow> rows, double& change,
                                     double& largest)
{
    // The arriving points' and the resting points' normal impulses, and the mechanism's joints',
    // at once, exactly (a small LCP by active sets, the joints' rows its equalities): a pinned
    // plank's four points on its stand stop its roll and its pitch only together, and sweeps
    // passed pushes between them for hundreds of rounds.
    m_normals.clear();
    for (std::size_t i = 0; i < m_jointEqualities.size(); ++i)
        m_normals.push_back({m_jointEqualities[i], &m_jointPushes[i]});
    for (ImpactRow& row : rows)
        m_normals.push_back({blowRow(c.a, c.b, row.rows, row.targetN), &row.pushN});
    for (RestingRow& row : m_resting)
        m_normals.push_back({blowRow(row.a, row.b, row.rows, row.targetN), &row.pushN});
    for (std::size_t i = 0; i < m_jointLimits.size(); ++i)
        m_normals.push_back({m_jointLimits[i], &m_jointPushes[m_jointEqualities.size() + i]});
    const std::size_t n = m_normals.size();
    const auto speed = [&](const BlowRow& row) { return row.speed(m_bodies[row.a], m_bodies[row.b]); };
    std::vector<double> now(n), b(n), x(n);
    for (std::size_t i = 0; i < n; ++i)
        now[i] = speed(m_normals[i].row);
    // A (the rows stay the same through the blow's sweeps).
    std::vector<double>& A = m_normalMatrix;
    if (!m_normalMatrixMade) {
        blowRowMatrix(
            m_bodies, n, [&](std::size_t i) -> const BlowRow& { return m_normals[i].row; },
            [&](const BlowRow& row, double lambda) { pushRow(row, lambda); }, A);
        m_normalMatrixMade = true;
    }
    // Speeds as functions of the total pushes x: w = A x + b, wanted w >= 0, x >= 0, x . w = 0
    // (w = 0 and x free on the joints' equalities).
    double scale = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
        b[i] = now[i] - m_normals[i].row.target;
        for (std::size_t j = 0; j < n; ++j)
            b[i] -= A[i * n + j] * *m_normals[j].push;
        scale = std::max(scale, std::abs(b[i]));
    }
    solveSmallLcp(A, b, n, 1e-12 * scale, x, m_jointEqualities.size());
    for (std::size_t i = 0; i < n; ++i) {
        NormalRow& row = m_normals[i];
        pushRow(row.row, x[i] - *row.push);
        change = std::max(change, std::abs(x[i] - *row.push));
        *row.push = x[i];
        largest = std::max(largest, std::abs(x[i]));
    }
}

bool ContactSolver::lookForBlow(std::size_t k, int maxStrikes)
{
    const IslandContact& c = m_constraints[k];
    const std::uint64_t blows = (std::uint64_t(m_blows[c.a]) << 32) | m_blows[c.b];
    if (blows == m_seen[k] || m_strikes[k] >= maxStrikes)
        return false;
    m_seen[k] = blows;
    if (!collideOne(c))
        return false;
    ++m_strikes[k];
    for (const BodyIndex body : {c.a, c.b})
        if (!m_bodies[body].isStatic()) // a static body never changes (and is shared)
            ++m_blows[body];
    return true;
}

ContactSolver::SurfacePoints ContactSolver::surfacePoints(double radiusA, double radiusB, const ContactPoint& p,
                                                         const dvec3& xa, const dmat3& ra, const dvec3& xb,
                                                         const dmat3& rb)
{
    SurfacePoints s;
    s.n = p.normal;
    if (radiusA > 0.0 && radiusB > 0.0) {
        // Two spheres touch along the line of their centres, wherever that has turned.
        const dvec3 d = xb - xa;
        if (const double len = glm::length(d); len > 0.0)
            s.n = d / len;
    }
    s.a = radiusA > 0.0 ? xa + radiusA * s.n : xa + ra * p.anchorA;
    s.b = radiusB > 0.0 ? xb - radiusB * s.n : xb + rb * p.anchorB;
    return s;
}

double ContactSolver::restitutionOf(const IslandContact& c, const PointRows& r) const
{
    // A method of order one does not keep the energy of a fall, but a modified one: along the
    // normal, with gap s, speed u and constant acceleration a, forward Euler keeps exactly
    // Q = u^2/2 - a s - a dt u / 2 and semi-implicit Euler Q = u^2/2 - a s + a dt u / 2 (velocity
    // Verlet and RK4 the energy itself), that is Q = u^2/2 - a s + (w - 1/2) a dt u with w the
    // method's drift weight. Its apex is where u = 0, at s = -Q/a. Leaving with the speed that
    // gives Q' = e^2 Q, rather than e times the speed of the exact arrival, makes the method's
    // own rebound reach e^2 times the height it fell from: the exact arrival would leave its
    // O(dt) error of the fall and of the rise in the bounce (3.7% each way for a 1 m drop at 60 Hz).
    // Returned as the ratio of that speed to the exact arrival's along the start's normal, which
    // is e itself where the acceleration along the normal is nil (two bodies both falling).
    const SolverBody& a = m_bodies[c.a];
    const SolverBody& b = m_bodies[c.b];
    const double dt = m_settings.dt;
    const double accel = (r.vnFree - r.vnStart) / dt;
    const double mass = a.inverseMass + b.inverseMass;
    const double w = mass > 0.0 ? (a.driftWeight * a.inverseMass + b.driftWeight * b.inverseMass) / mass : 1.0;
    const double k = (w - 0.5) * accel * dt;
    const double q = 0.5 * r.vnStart * r.vnStart - accel * std::max(r.separation, 0.0) + k * r.vnStart;
    const double e2q = c.restitution * c.restitution * q;
    const double exact2 = r.vnStart * r.vnStart - 2.0 * accel * std::max(r.separation, 0.0);
    if (k == 0.0 || !(k * k + 2.0 * e2q >= 0.0) || !(exact2 > m_settings.restingSpeed * m_settings.restingSpeed))
        return c.restitution;
    // An O(dt) correction of e: never past the bounds a restitution has.
    return std::clamp((-k + std::sqrt(k * k + 2.0 * e2q)) / std::sqrt(exact2), 0.0, 1.0);
}

double ContactSolver::refineArrival(const IslandContact& c, int point, double tPrev, double tau) const
{
    // The estimate took the gap along the start's normal as changing at a constant rate; along
    // the free paths themselves (turning, and off-centre for two spheres) it closes a little
    // sooner or later. Newton's method on the gap between the two surface points, a few times.
    const SolverBody& a = m_bodies[c.a];
    const SolverBody& b = m_bodies[c.b];
    const double dt = m_settings.dt;
    const ContactPoint& p = m_contacts[c.contact].points[point];
    for (int k = 0; k < 8; ++k) {
        const double f = tau / dt;
        const dvec3 xa = a.freePosition(f, dt), xb = b.freePosition(f, dt);
        const SurfacePoints sp = surfacePoints(c.radiusA, c.radiusB, p, xa, glm::mat3_cast(a.freeOrientation(f)), xb,
                                               glm::mat3_cast(b.freeOrientation(f)));
        const double gap = glm::dot(sp.b - sp.a, sp.n);
        const dvec3 u = b.velocityAt(f) + glm::cross(b.spinAt(f), sp.b - xb) - a.velocityAt(f) -
                        glm::cross(a.spinAt(f), sp.a - xa);
        const double closing = glm::dot(u, sp.n);
        if (!(closing < 0.0))
            break;
        const double next = std::clamp(tau - gap / closing, tPrev, dt);
        if (std::abs(next - tau) <= 1e-15 * dt)
            break;
        tau = next;
    }
    return tau;
}

bool ContactSolver::firstArrival(const IslandContact& c, double& tau, bool (&arrives)[kMaxPoints]) const
{
    // When each point arrives: its gap moves with the start's velocities up to the last impulse
    // either body took this step (tPrev), and from then with the present ones, the free step's
    // acceleration taken as constant throughout.
    const SolverBody& a = m_bodies[c.a];
    const SolverBody& b = m_bodies[c.b];
    const double dt = m_settings.dt;
    const double tPrev = std::max(a.lastImpact, b.lastImpact);
    tau = dt;
    bool any = false;
    int first = 0;
    for (int i = 0; i < c.count; ++i) {
        const PointRows& r = m_rows[c.first + i];
        const double accel = (r.vnFree - r.vnStart) / dt;
        const double vn = glm::dot(r.n, relativeVelocity(a, b, r));
        const double gap = r.separation + r.vnStart * tPrev + 0.5 * accel * tPrev * tPrev;
        const double speed = vn - accel * (dt - tPrev);
        const double s = arrival(gap, speed, accel, dt - tPrev);
        if (std::isnan(s) || !(speed + accel * s < -m_settings.restingSpeed))
            continue;
        arrives[i] = true;
        if (tPrev + s < tau) {
            tau = tPrev + s;
            first = i;
        }
        any = true;
    }
    if (any)
        tau = refineArrival(c, first, tPrev, tau);
    return any;
}

int ContactSolver::impactRows(const IslandContact& c, double tau, const bool (&arrives)[kMaxPoints],
                              ImpactRow (&rows)[kMaxPoints]) const
{
    // The impulses act at tau, at the points where the bodies' free paths had them then, both
    // bodies' arms reaching one point: so they change the total momentum and angular momentum by
    // nothing, and the energy by exactly what restitution and friction take.
    const SolverBody& a = m_bodies[c.a];
    const SolverBody& b = m_bodies[c.b];
    const double f = tau / m_settings.dt;
    const dvec3 xa = a.freePosition(f, m_settings.dt), xb = b.freePosition(f, m_settings.dt);
    const dmat3 qa = glm::mat3_cast(a.freeOrientation(f)), qb = glm::mat3_cast(b.freeOrientation(f));
    const dvec3 va = a.velocityAt(f), wa = a.spinAt(f), vb = b.velocityAt(f), wb = b.spinAt(f);
    int count = 0;
    for (int i = 0; i < c.count; ++i) {
        if (!arrives[i])
            continue;
        const SurfacePoints sp = surfacePoints(c.radiusA, c.radiusB, m_contacts[c.contact].points[i], xa, qa, xb, qb);
        ImpactRow& row = rows[count];
        // A sphere touches at its own surface point on the normal, exactly: the other shape's
        // point was found at the start, and a sphere sliding in across a face has moved on since
        // (their midpoint would lever the sphere into a spin no frictionless contact gives).
        const bool sphereA = c.radiusA > 0.0, sphereB = c.radiusB > 0.0;
        const dvec3 p = sphereA && !sphereB ? sp.a : sphereB && !sphereA ? sp.b : 0.5 * (sp.a + sp.b);
        row.point = i;
        row.rows.rA = p - xa;
        row.rows.rB = p - xb;
        row.rows.n = sp.n;
        tangentsOf(sp.n, row.rows.t);
        row.rows.normalMass = blowMass(c.a, c.b, row.rows.rA, row.rows.rB, sp.n);
        const dvec3 atImpact = vb + glm::cross(wb, row.rows.rB) - va - glm::cross(wa, row.rows.rA);
        const double arriving = glm::dot(sp.n, atImpact);
        if (!(arriving < -m_settings.restingSpeed))
            continue; // it meets the surface turning away from it
        const dvec3 now = relativeVelocity(a, b, row.rows);
        // The method's own energy describes a fall from the start of the step, not an arrival that
        // an earlier blow in this step set off: then the restitution is e itself.
        const bool ownFall = !a.struck && !b.struck;
        const double leaving = -arriving * (ownFall ? restitutionOf(c, m_rows[c.first + i]) : c.restitution);
        row.targetN = glm::dot(sp.n, now) + (leaving - arriving);
        for (int k = 0; k < 2; ++k) {
            row.rows.tangentMass[k] = blowMass(c.a, c.b, row.rows.rA, row.rows.rB, row.rows.t[k]);
            row.targetT[k] = glm::dot(row.rows.t[k], now - atImpact); // its sliding at arrival stopped
        }
        ++count;
    }
    return count;
}

void ContactSolver::solveImpact(const IslandContact& c, std::span<ImpactRow> rows)
{
    // The arriving points' impulses together, to convergence: each leaves at e times its
    // arriving speed, and slides no faster than friction lets it.
    SolverBody& a = m_bodies[c.a];
    SolverBody& b = m_bodies[c.b];
    const bool exact = !m_resting.empty() || !m_jointEqualities.empty() || !m_jointLimits.empty();
    m_normalMatrixMade = false;
    for (int sweep = 0; sweep < kMaxImpactSweeps; ++sweep) {
        double change = 0.0, largest = 0.0;
        for (ImpactRow& row : rows) {
            const PointRows& r = row.rows;
            double want[2];
            for (int k = 0; k < 2; ++k)
                want[k] = row.pushT[k] - r.tangentMass[k] * (glm::dot(r.t[k], relativeVelocity(a, b, r)) - row.targetT[k]);
            const double length = std::sqrt(want[0] * want[0] + want[1] * want[1]);
            const double limit = c.friction * row.pushN;
            const double scale = length > limit ? limit / length : 1.0;
            for (int k = 0; k < 2; ++k) {
                const double next = want[k] * scale;
                applyBlow(c.a, c.b, r, (next - row.pushT[k]) * r.t[k]);
                change = std::max(change, std::abs(next - row.pushT[k]));
                row.pushT[k] = next;
            }
            if (exact)
                continue; // the normals all together, below
            const double vn = glm::dot(r.n, relativeVelocity(a, b, r));
            const double next = std::max(row.pushN - r.normalMass * (vn - row.targetN), 0.0);
            applyBlow(c.a, c.b, r, (next - row.pushN) * r.n);
            change = std::max(change, std::abs(next - row.pushN));
            row.pushN = next;
            largest = std::max(largest, next);
        }
        if (exact)
            solveBlowNormals(c, rows, change, largest);
        if (m_impactJoints)
            m_impactJoints->sweepBlow();
        if (change <= 1e-12 * largest)
            break;
    }
}

bool ContactSolver::collideOne(const IslandContact& c)
{
    double tau = 0.0;
    bool arrives[kMaxPoints] = {};
    if (!firstArrival(c, tau, arrives))
        return false;
    ImpactRow rows[kMaxPoints];
    const int count = impactRows(c, tau, arrives, rows);
    if (count == 0)
        return false;
    SolverBody& a = m_bodies[c.a];
    SolverBody& b = m_bodies[c.b];
    const dvec3 va0 = a.v, wa0 = a.w, vb0 = b.v, wb0 = b.w;
    m_resting.clear();
    m_mechanism.clear();
    m_jointEqualities.clear();
    m_jointLimits.clear();
    if (m_impactJoints)
        m_impactJoints->mechanismRows(c.a, c.b, m_mechanism, m_jointEqualities, m_jointLimits);
    m_jointPushes.assign(m_jointEqualities.size() + m_jointLimits.size(), 0.0);
    if (!m_pins.empty() || !m_mechanism.empty() || farLighterIn(c, c.a) || farLighterIn(c, c.b))
        restingRows(c, std::span(rows, std::size_t(count)));
    const std::span<const BodyIndex> joined = m_impactJoints ? m_impactJoints->bodies() : std::span<const BodyIndex>();
    m_jointBodiesBefore.clear();
    for (const BodyIndex k : joined)
        m_jointBodiesBefore.emplace_back(m_bodies[k].v, m_bodies[k].w);
    solveImpact(c, std::span(rows, std::size_t(count)));
    // The end poses move by the velocity change over what is left of the step.
    const double left = m_settings.dt - tau;
    const auto shift = [&](SolverBody& body, const dvec3& v0, const dvec3& w0) {
        if (body.isStatic())
            return;
        body.shift += (body.v - v0) * left;
        body.turn += (body.w - w0) * left;
        body.lastImpact = tau;
        body.struck = true;
    };
    shift(a, va0, wa0);
    shift(b, vb0, wb0);
    // The bodies the joints moved with the blow: theirs too, and their contacts are looked at again.
    for (std::size_t i = 0; i < joined.size(); ++i) {
        SolverBody& body = m_bodies[joined[i]];
        const auto [v0, w0] = m_jointBodiesBefore[i];
        if (joined[i] == c.a || joined[i] == c.b || (body.v == v0 && body.w == w0))
            continue;
        shift(body, v0, w0);
        ++m_blows[joined[i]];
    }
    for (int i = 0; i < count; ++i) {
        m_rows[c.first + rows[i].point].bounced = true;
        VelocityRows& v = m_velocityRows[c.first + rows[i].point];
        v.normalImpulse = 0.0; // its warm start was a resting push: not for a bounce
        v.tangentImpulse[0] = v.tangentImpulse[1] = 0.0;
    }
    return true;
}

} // namespace pba::rigid
