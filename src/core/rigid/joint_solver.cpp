#include "rigid/joint_solver.hpp"

#include <algorithm>
#include <cmath>

namespace pba::rigid {

namespace {

dmat3 inverseOr0(const dmat3& k)
{
    const double det = glm::determinant(k);
    return det != 0.0 && std::isfinite(det) ? glm::inverse(k) : dmat3(0.0);
}

/// The 2x2 block of K on two directions, inverted and put back into a 3x3 on those directions:
/// an angular impulse sum_k lambda_k t_k with lambda = M c.
struct Block2 {
    double m[2][2] = {{0.0, 0.0}, {0.0, 0.0}};
};

Block2 inverse2(const dmat3& k, const dvec3 (&t)[2])
{
    const double a = glm::dot(t[0], k * t[0]), b = glm::dot(t[0], k * t[1]), d = glm::dot(t[1], k * t[1]);
    const double det = a * d - b * b;
    Block2 out;
    if (det > 0.0) {
        out.m[0][0] = d / det;
        out.m[0][1] = out.m[1][0] = -b / det;
        out.m[1][1] = a / det;
    }
    return out;
}

/// The angular impulse that cancels `c` (a relative angular quantity) across the axis.
dvec3 acrossImpulse(const Block2& mass, const dvec3 (&t)[2], const dvec3& c)
{
    const double c0 = glm::dot(t[0], c), c1 = glm::dot(t[1], c);
    return -(mass.m[0][0] * c0 + mass.m[0][1] * c1) * t[0] - (mass.m[1][0] * c0 + mass.m[1][1] * c1) * t[1];
}

void applyLinear(SolverBody& a, SolverBody& b, const dvec3& ra, const dvec3& rb, const dvec3& p)
{
    a.applyImpulse(-p, ra);
    b.applyImpulse(p, rb);
}

void applyAngular(SolverBody& a, SolverBody& b, const dvec3& l)
{
    a.applyAngularImpulse(-l);
    b.applyAngularImpulse(l);
}

dvec3 anchorVelocity(const SolverBody& a, const SolverBody& b, const dvec3& ra, const dvec3& rb)
{
    return b.pointVelocity(rb) - a.pointVelocity(ra);
}

/// What an angular impulse l with the linear impulse carry * l that keeps the anchors' relative
/// velocity does to the bodies' relative spin: S l, S the Schur complement of the joint's 6x6 K
/// (the anchors' 3x3 block eliminated). Without the carry, S is IA^-1 + IB^-1.
struct Carried {
    dmat3 spin{0.0};  ///< S
    dmat3 carry{0.0}; ///< -K_pp^-1 C, C the anchors' velocity change per angular impulse
};

Carried carriedWith(const SolverBody& a, const SolverBody& b, const dvec3& ra, const dvec3& rb)
{
    // l turns A by -IA^-1 l and B by IB^-1 l: the anchors' relative velocity changes by C l.
    const dmat3 c = -(skew(rb) * b.inverseInertia + skew(ra) * a.inverseInertia);
    Carried out;
    out.carry = -(inverseOr0(pointMass(a, b, ra, rb)) * c);
    out.spin = a.inverseInertia + b.inverseInertia + glm::transpose(c) * out.carry;
    return out;
}

/// How many times a Verlet-type spring's line is found again (prepareSpring).
constexpr int kSpringLineRounds = 6;

/// Two unit vectors across `axis` (unit).
void acrossOf(const dvec3& axis, dvec3 (&t)[2]) { tangentsOf(axis, t); }

} // namespace

double hingeAngle(const Joint& j, const dquat& qa, const dquat& qb)
{
    const dvec3 axis = glm::mat3_cast(qa) * j.axisA;
    const dvec3 ra = glm::mat3_cast(qa) * j.refA, rb = glm::mat3_cast(qb) * j.refB;
    return std::atan2(glm::dot(glm::cross(rb, ra), axis), glm::dot(ra, rb));
}

JointSolver::Rows JointSolver::rowsAt(std::uint32_t index, Pose pose) const
{
    const Joint& j = m_joints[index];
    Rows r;
    r.joint = index;
    r.a = j.a == kWorldBody ? m_world : j.a;
    r.b = j.b == kWorldBody ? m_world : j.b;
    const SolverBody& a = m_bodies[r.a];
    const SolverBody& b = m_bodies[r.b];
    const bool atEnd = pose == Pose::End;
    const auto position = [&](const SolverBody& k) { return atEnd && !k.isStatic() ? k.endPosition : k.position; };
    const auto orientation = [&](const SolverBody& k) {
        return atEnd && !k.isStatic() ? k.endOrientation : k.orientation;
    };
    const dmat3 ra = glm::mat3_cast(orientation(a)), rb = glm::mat3_cast(orientation(b));
    r.rA = ra * j.localA;
    r.rB = rb * j.localB;
    r.linearMass = inverseOr0(pointMass(a, b, r.rA, r.rB));
    const bool turns = j.type == JointType::Hinge || j.type == JointType::Fixed; // has angular rows
    const Carried carried = turns ? carriedWith(a, b, r.rA, r.rB) : Carried{};
    const dmat3& angular = carried.spin;
    r.carry = carried.carry;
    if (j.type == JointType::Hinge) {
        r.axis = glm::normalize(ra * j.axisA);
        acrossOf(r.axis, r.across);
        const Block2 m = inverse2(angular, r.across);
        for (int p = 0; p < 2; ++p)
            for (int q = 0; q < 2; ++q)
                r.acrossMass[p][q] = m.m[p][q];
        const double k = glm::dot(r.axis, angular * r.axis);
        r.axialMass = k > 0.0 ? 1.0 / k : 0.0;
        r.angle = hingeAngle(j, orientation(a), orientation(b));
    } else if (j.type == JointType::Fixed) {
        r.angularMass = inverseOr0(angular);
    } else if (j.type == JointType::Distance) {
        const dvec3 d = (position(b) + r.rB) - (position(a) + r.rA);
        const double len = glm::length(d);
        r.n = len > 0.0 ? d / len : dvec3(0.0, 1.0, 0.0);
        if (j.stiffness > 0.0) {
            if (!atEnd) // (a spring is no equality: never projected at the end)
                prepareSpring(j, r, a, b, d, m_settings.dt);
        } else {
            const double k = glm::dot(r.n, pointMass(a, b, r.rA, r.rB) * r.n);
            r.axialMass = k > 0.0 ? 1.0 / k : 0.0;
        }
    }
    return r;
}

namespace {

/// Whether a joint is solved as RATTLE (JointSolver's header): an equality (a ball joint, a
/// hinge without limits, a weld, a rod) whose moving bodies all take velocity Verlet's kind of
/// step (drift weight 1/2). A limit, like a contact, may only push.
bool rattles(const Joint& j, const SolverBody& a, const SolverBody& b)
{
    const bool equality = j.type == JointType::Ball || j.type == JointType::Fixed ||
                          (j.type == JointType::Hinge && !j.limited) ||
                          (j.type == JointType::Distance && !(j.stiffness > 0.0));
    const auto verlet = [](const SolverBody& k) { return k.isStatic() || k.driftWeight == 0.5; };
    return equality && !(a.isStatic() && b.isStatic()) && verlet(a) && verlet(b);
}

} // namespace

void JointSolver::prepare(std::span<Joint> joints, std::span<const std::uint32_t> island, std::span<SolverBody> bodies,
                          const SolverSettings& settings, BodyIndex world)
{
    m_joints = joints;
    m_bodies = bodies;
    m_settings = settings;
    m_world = world;
    m_rows.clear();
    for (const std::uint32_t index : island) {
        const Joint& j = joints[index];
        Rows r = rowsAt(index, Pose::Start);
        r.rattle = rattles(j, bodies[r.a], bodies[r.b]);
        r.linearImpulse = j.linearImpulse;
        r.angularImpulse = j.angularImpulse;
        // A hinge's rows across its axis hold no turn about it: the last step's impulse, kept as
        // a world vector, is warm-started across the axis as it is now. (Its part along a tilted
        // axis that had turned since was a push about the free axis, which no sweep takes back:
        // two rods hinged on skew axes gained energy until the cap stopped them dead.)
        if (j.type == JointType::Hinge)
            r.angularImpulse -= glm::dot(r.angularImpulse, r.axis) * r.axis;
        r.axialImpulse = j.axialImpulse;
        r.lowerImpulse = j.lowerImpulse;
        r.upperImpulse = j.upperImpulse;
        m_rows.push_back(r);
    }
    m_farApart = false;
    for (const Rows& r : m_rows) {
        const double wa = bodies[r.a].inverseMass, wb = bodies[r.b].inverseMass;
        const bool spring = joints[r.joint].type == JointType::Distance && joints[r.joint].stiffness > 0.0;
        const bool far = wa > 0.0 && wb > 0.0 && std::max(wa, wb) > kFarLighter * std::min(wa, wb);
        m_farApart = m_farApart || (!spring && far);
    }
    m_movingBodies.clear();
    for (const Rows& r : m_rows)
        for (const BodyIndex k : {r.a, r.b})
            if (!bodies[k].isStatic())
                m_movingBodies.push_back(k);
    std::sort(m_movingBodies.begin(), m_movingBodies.end());
    m_movingBodies.erase(std::unique(m_movingBodies.begin(), m_movingBodies.end()), m_movingBodies.end());
}

void JointSolver::warmStart()
{
    for (const Rows& r : m_rows) {
        const Joint& j = m_joints[r.joint];
        SolverBody& a = m_bodies[r.a];
        SolverBody& b = m_bodies[r.b];
        if (j.type == JointType::Distance) {
            applyLinear(a, b, r.rA, r.rB, (r.axialImpulse + r.startImpulse) * r.n);
            continue;
        }
        applyLinear(a, b, r.rA, r.rB, r.linearImpulse);
        applyAngular(a, b, r.angularImpulse - (r.lowerImpulse - r.upperImpulse) * r.axis);
    }
}

double JointSolver::explicitSpringWork() const
{
    std::vector<std::pair<BodyIndex, std::pair<dvec3, dvec3>>> kicks; // a body's dv and dw
    const auto kick = [&](BodyIndex k, const dvec3& p, const dvec3& r) {
        const SolverBody& body = m_bodies[k];
        if (body.isStatic())
            return;
        auto at = std::find_if(kicks.begin(), kicks.end(), [&](const auto& e) { return e.first == k; });
        if (at == kicks.end())
            at = kicks.insert(kicks.end(), {k, {dvec3(0.0), dvec3(0.0)}});
        at->second.first += body.inverseMass * p;
        at->second.second += body.inverseInertia * glm::cross(r, p);
    };
    for (const Rows& r : m_rows) {
        const Joint& j = m_joints[r.joint];
        if (j.type != JointType::Distance || !(j.stiffness > 0.0) || r.endStiffness != 0.0 || r.startImpulse == 0.0)
            continue;
        kick(r.a, -r.startImpulse * r.n, r.rA);
        kick(r.b, r.startImpulse * r.n, r.rB);
    }
    double work = 0.0;
    for (const auto& [k, change] : kicks) {
        const SolverBody& b = m_bodies[k];
        const dvec3 v = b.vFree + change.first, w = b.wFree + change.second;
        work += 0.5 * (glm::dot(v, v) - glm::dot(b.vFree, b.vFree)) / b.inverseMass +
                0.5 * (glm::dot(w, b.inertia * w) - glm::dot(b.wFree, b.inertia * b.wFree));
    }
    return work;
}

void JointSolver::solveBall(Rows& r, SolverBody& a, SolverBody& b)
{
    const dvec3 lambda = -(r.linearMass * rowAnchorVelocity(r, a, b));
    r.linearImpulse += lambda;
    applyLinear(a, b, r.rA, r.rB, lambda);
}

void JointSolver::applyCarried(Rows& r, SolverBody& a, SolverBody& b, const dvec3& l)
{
    applyAngular(a, b, l);
    const dvec3 p = r.carry * l;
    r.linearImpulse += p;
    applyLinear(a, b, r.rA, r.rB, p);
}

dvec3 JointSolver::carriedSpin(const Rows& r, const SolverBody& a, const SolverBody& b)
{
    // The rows' unknowns are angular impulses with their carried linear ones: the spin they
    // are solved for counts the anchors' relative velocity along the carry too, so that each is
    // the least-energy step along its impulses (a Gauss-Seidel step; a chain flew apart without).
    return (b.w - a.w - r.blowSpin) + glm::transpose(r.carry) * rowAnchorVelocity(r, a, b);
}

dvec3 JointSolver::rowAnchorVelocity(const Rows& r, const SolverBody& a, const SolverBody& b)
{
    return anchorVelocity(a, b, r.rA, r.rB) - r.blowAnchor;
}

void JointSolver::solveHingeAngular(const Joint& j, Rows& r, SolverBody& a, SolverBody& b)
{
    // Across the axis the two bodies turn together.
    const Block2 mass{{{r.acrossMass[0][0], r.acrossMass[0][1]}, {r.acrossMass[1][0], r.acrossMass[1][1]}}};
    const dvec3 l = acrossImpulse(mass, r.across, carriedSpin(r, a, b));
    r.angularImpulse += l;
    applyCarried(r, a, b, l);
    if (!j.limited)
        return;
    // About it, the angle may close its gap to a limit within the step, not cross it (as a
    // speculative contact): at the lower limit A's spin relative to B about the axis is at least
    // -(angle - lower) / dt, with an impulse that only turns A forwards; at the upper, at most
    // (upper - angle) / dt. (An angular impulse l applied as below turns A by -l, B by +l.)
    // In a blow the rows measure the blow's change of that spin: it may bring the spin up to the
    // bound, or leave it where the free step had it beyond (the velocity sweeps' work), and
    // a hinge far from its limits turns freely.
    const double dt = m_settings.dt;
    const double before = m_inBlows ? r.blowAxialSpin : 0.0;
    {
        const double spin = -glm::dot(r.axis, carriedSpin(r, a, b));
        const double bound = -std::max(r.angle - j.lower, 0.0) / dt - before;
        const double target = m_inBlows ? std::min(bound, 0.0) : bound;
        const double next = std::max(r.lowerImpulse - r.axialMass * (spin - target), 0.0);
        applyCarried(r, a, b, -(next - r.lowerImpulse) * r.axis);
        r.lowerImpulse = next;
    }
    {
        const double spin = -glm::dot(r.axis, carriedSpin(r, a, b));
        const double bound = std::max(j.upper - r.angle, 0.0) / dt - before;
        const double target = m_inBlows ? std::max(bound, 0.0) : bound;
        const double next = std::max(r.upperImpulse + r.axialMass * (spin - target), 0.0);
        applyCarried(r, a, b, (next - r.upperImpulse) * r.axis);
        r.upperImpulse = next;
    }
}

void JointSolver::solveFixedAngular(Rows& r, SolverBody& a, SolverBody& b)
{
    const dvec3 l = -(r.angularMass * carriedSpin(r, a, b));
    r.angularImpulse += l;
    applyCarried(r, a, b, l);
}

void JointSolver::prepareSpring(const Joint& j, Rows& r, const SolverBody& a, const SolverBody& b, const dvec3& d,
                                double dt)
{
    // The spring's impulse over the step weighs its start's stretch and its end's as the body's
    // method weighs the start and end velocities in the position's update (driftWeight): the
    // end's alone under semi-implicit Euler, implicitly, with the damping (a soft constraint,
    // Catto's "Soft Constraints"); half each under velocity Verlet, the splitting and RK4, along
    // the mean of the start's and end's lines and scaled by |d0 + d1| / (|d0| + |d1|), which
    // keeps the spring's energy exactly over a step that the two anchors drift by the mean of
    // their velocities (a discrete gradient, Gonzalez); the start's alone under forward Euler.
    // Taken at the end alone under a Verlet-type method, the start velocity's half of the drift
    // left the swing's turn out of the position, and a ball circling on a spring gained energy
    // every step.
    const dmat3 ma = bodyPointMass(a, r.rA), mb = bodyPointMass(b, r.rB);
    const double ka = glm::dot(r.n, ma * r.n), kb = glm::dot(r.n, mb * r.n);
    const double wa = a.driftWeight, wb = b.driftWeight;
    const double endShare = ka + kb > 0.0 ? (wa * ka + wb * kb) / (ka + kb) : 1.0;
    const double start = glm::dot(r.n, d) - j.length;
    r.startImpulse = -(1.0 - endShare) * dt * j.stiffness * start;
    double stretchScale = 1.0;
    r.endLine = r.n;
    if (endShare < 1.0) {
        // Where the free step and the start's share leave the two anchors, and the line between
        // the start's and that: the start's share acts along the line it depends on, found
        // again a few times (each time closer by the square of the step's turn).
        const auto drifted = [&](const SolverBody& body, const dvec3& arm, const dvec3& kick) {
            const double w = body.driftWeight;
            return (1.0 - w) * body.pointStartVelocity(arm) + w * (body.pointVelocity(arm) + kick);
        };
        const double startLength = glm::length(d);
        const double startImpulse = r.startImpulse;
        for (int round = 0; round < kSpringLineRounds; ++round) {
            const dvec3 kick = r.startImpulse * r.n;
            const dvec3 end = d + dt * (drifted(b, r.rB, mb * kick) - drifted(a, r.rA, -(ma * kick)));
            const double endLength = glm::length(end);
            const dvec3 mean = d + end;
            const double meanLength = glm::length(mean);
            if (!(endLength > 0.0 && meanLength > 0.0))
                break;
            r.endLine = end / endLength;
            r.n = mean / meanLength;
            stretchScale = meanLength / (startLength + endLength);
            r.startImpulse = startImpulse * stretchScale;
        }
    }
    // The stretch at the end as the velocities drive it: springStretch + dt e . (wB vB - wA vA),
    // e the end's line.
    const dvec3& e = r.endLine;
    r.springStretch = glm::dot(e, d) - j.length +
                      dt * glm::dot(e, (1.0 - wb) * b.pointStartVelocity(r.rB) - (1.0 - wa) * a.pointStartVelocity(r.rA));
    const double k = glm::dot(r.n, (ma + mb) * r.n);
    const double kw = glm::dot(e, (wa * ma + wb * mb) * r.n);
    r.endStiffness = endShare * stretchScale * j.stiffness;
    r.springGain = 1.0 / (1.0 + dt * (r.endStiffness * dt * kw + j.damping * k));
}

void JointSolver::solveDistance(const Joint& j, Rows& r, SolverBody& a, SolverBody& b)
{
    const double speed = glm::dot(r.n, rowAnchorVelocity(r, a, b));
    double lambda = -r.axialMass * speed;
    if (j.stiffness > 0.0) {
        // The impulse so far must equal -dt (endStiffness stretchAtEnd + c speed); the sweep moves it there.
        const double dt = m_settings.dt;
        const double drive =
            glm::dot(r.endLine, b.driftWeight * b.pointVelocity(r.rB) - a.driftWeight * a.pointVelocity(r.rA));
        const double stretch = r.springStretch + dt * drive;
        lambda = -r.springGain * (dt * (r.endStiffness * stretch + j.damping * speed) + r.axialImpulse);
    }
    r.axialImpulse += lambda;
    applyLinear(a, b, r.rA, r.rB, lambda * r.n);
}

void JointSolver::solveVelocities() { sweep(m_rows, false); }

void JointSolver::beginBlows()
{
    // A blow's sweeps keep each joint's relative velocities as they were before it: they take
    // away what the blow does to the joints, and leave what the free step did to the velocity
    // sweeps and their warm start (driven to zero here too, it was taken twice, and a chain
    // struck against a wall tilted out of its plane by 7 degrees).
    m_rowsBeforeBlows = m_rows;
    for (Rows& r : m_rows) {
        r.linearImpulse = r.angularImpulse = dvec3(0.0);
        r.axialImpulse = r.lowerImpulse = r.upperImpulse = 0.0;
        const SolverBody& a = m_bodies[r.a];
        const SolverBody& b = m_bodies[r.b];
        r.blowAxialSpin = -glm::dot(r.axis, carriedSpin(r, a, b));
        r.blowAnchor = anchorVelocity(a, b, r.rA, r.rB);
        r.blowSpin = b.w - a.w;
    }
    m_inBlows = true;
    findPins();
}

void JointSolver::findPins()
{
    m_pins.clear();
    std::vector<int> joints(m_movingBodies.size(), 0);
    const auto slot = [&](BodyIndex k) {
        return std::size_t(std::lower_bound(m_movingBodies.begin(), m_movingBodies.end(), k) - m_movingBodies.begin());
    };
    for (const Rows& r : m_rows)
        for (const BodyIndex k : {r.a, r.b})
            if (!m_bodies[k].isStatic())
                ++joints[slot(k)];
    for (const Rows& r : m_rows) {
        const Joint& j = m_joints[r.joint];
        const bool aMoves = !m_bodies[r.a].isStatic(), bMoves = !m_bodies[r.b].isStatic();
        if (aMoves == bMoves || j.type == JointType::Distance)
            continue;
        const BodyIndex k = aMoves ? r.a : r.b;
        // A particle (a point body, which does not turn) keeps the sweeps: held at its centre, it
        // has no turn to take.
        if (joints[slot(k)] != 1 || m_bodies[k].inverseInertia == dmat3(0.0))
            continue;
        if (j.type == JointType::Hinge && j.limited &&
            std::min(r.angle - j.lower, j.upper - r.angle) < kPinLimitGap)
            continue;
        const SolverBody& body = m_bodies[k];
        Pin pin;
        pin.body = k;
        pin.arm = -(aMoves ? r.rA : r.rB);
        // Its inertia about the anchor: the centre's, and its mass at the arm (parallel axes).
        const dvec3 d = pin.arm;
        const dmat3 about = body.inertia + (glm::dot(d, d) * dmat3(1.0) - glm::outerProduct(d, d)) / body.inverseMass;
        if (j.type == JointType::Ball)
            pin.inverseInertia = glm::inverse(about);
        else if (j.type == JointType::Hinge)
            pin.inverseInertia = glm::outerProduct(r.axis, r.axis) / glm::dot(r.axis, about * r.axis);
        m_pins.push_back(pin); // a fixed joint's: no turn at all
    }
}

bool JointSolver::mechanismOf(BodyIndex x, BodyIndex y, std::vector<BodyIndex>& bodies, std::vector<char>& taken) const
{
    const auto pinned = [&](BodyIndex k) {
        return std::any_of(m_pins.begin(), m_pins.end(), [&](const Pin& p) { return p.body == k; });
    };
    const auto joined = [&](BodyIndex k) { return std::find(bodies.begin(), bodies.end(), k) != bodies.end(); };
    for (const BodyIndex k : {x, y})
        if (!m_bodies[k].isStatic() && !joined(k) && !pinned(k) &&
            std::binary_search(m_movingBodies.begin(), m_movingBodies.end(), k))
            bodies.push_back(k);
    // The bodies' joints (not springs, which pass no blow), and the bodies at their other ends,
    // until no joint adds one.
    taken.assign(m_rows.size(), 0);
    for (bool grew = !bodies.empty(); grew;) {
        grew = false;
        for (std::size_t i = 0; i < m_rows.size(); ++i) {
            const Rows& r = m_rows[i];
            const Joint& j = m_joints[r.joint];
            if (taken[i] || (j.type == JointType::Distance && j.stiffness > 0.0) || !(joined(r.a) || joined(r.b)))
                continue;
            taken[i] = 1;
            grew = true;
            for (const BodyIndex k : {r.a, r.b})
                if (!m_bodies[k].isStatic() && !joined(k))
                    bodies.push_back(k);
        }
    }
    const auto point = [&](BodyIndex k) { return m_bodies[k].inverseInertia == dmat3(0.0); };
    return !bodies.empty() && std::none_of(bodies.begin(), bodies.end(), point);
}

void JointSolver::blowRowsOf(const Rows& r, std::vector<BlowRow>& equalities, std::vector<BlowRow>& limits) const
{
    const Joint& j = m_joints[r.joint];
    const auto linear = [&](const dvec3& n) {
        equalities.push_back({r.a, r.b, r.rA, r.rB, n, false, glm::dot(n, r.blowAnchor)});
    };
    const auto angular = [&](const dvec3& n) {
        equalities.push_back({r.a, r.b, r.rA, r.rB, n, true, glm::dot(n, r.blowSpin)});
    };
    if (j.type == JointType::Distance) {
        linear(r.n);
        return;
    }
    const dvec3 frame[3] = {dvec3(1.0, 0.0, 0.0), dvec3(0.0, 1.0, 0.0), dvec3(0.0, 0.0, 1.0)};
    for (const dvec3& n : frame)
        linear(n);
    if (j.type == JointType::Fixed)
        for (const dvec3& n : frame)
            angular(n);
    if (j.type != JointType::Hinge)
        return;
    angular(r.across[0]);
    angular(r.across[1]);
    if (!j.limited)
        return;
    // As solveHingeAngular's limit rows in a blow: A's spin relative to B's about the axis may
    // change only as far as closes the gap within the step.
    const double dt = m_settings.dt, before = r.blowAxialSpin;
    const double lower = std::min(-std::max(r.angle - j.lower, 0.0) / dt - before, 0.0);
    const double upper = std::max(std::max(j.upper - r.angle, 0.0) / dt - before, 0.0);
    limits.push_back({r.a, r.b, r.rA, r.rB, -r.axis, true, lower - glm::dot(r.axis, r.blowSpin)});
    limits.push_back({r.a, r.b, r.rA, r.rB, r.axis, true, -upper + glm::dot(r.axis, r.blowSpin)});
}

bool JointSolver::mechanismRows(BodyIndex x, BodyIndex y, std::vector<BodyIndex>& bodies,
                                std::vector<BlowRow>& equalities, std::vector<BlowRow>& limits) const
{
    bodies.clear();
    equalities.clear();
    limits.clear();
    std::vector<char> taken;
    const bool found = mechanismOf(x, y, bodies, taken);
    if (found)
        for (std::size_t i = 0; i < m_rows.size(); ++i)
            if (taken[i])
                blowRowsOf(m_rows[i], equalities, limits);
    if (!found || equalities.size() + limits.size() > kMaxMechanismRows) {
        bodies.clear();
        equalities.clear();
        limits.clear();
        return false;
    }
    return true;
}

void JointSolver::sweepBlow() { sweep(m_rows, true); }

void JointSolver::endBlows()
{
    m_rows.swap(m_rowsBeforeBlows);
    m_inBlows = false;
}

void JointSolver::sweep(std::vector<Rows>& rows, bool blow)
{
    for (Rows& r : rows) {
        const Joint& j = m_joints[r.joint];
        if (blow && j.type == JointType::Distance && j.stiffness > 0.0)
            continue; // a spring's force passes nothing in an instant
        SolverBody& a = m_bodies[r.a];
        SolverBody& b = m_bodies[r.b];
        switch (j.type) {
        case JointType::Ball: solveBall(r, a, b); break;
        case JointType::Hinge:
            solveHingeAngular(j, r, a, b);
            solveBall(r, a, b);
            break;
        case JointType::Fixed:
            solveFixedAngular(r, a, b);
            solveBall(r, a, b);
            break;
        case JointType::Distance: solveDistance(j, r, a, b); break;
        }
    }
}

void JointSolver::storeImpulses()
{
    for (const Rows& r : m_rows) {
        Joint& j = m_joints[r.joint];
        j.linearImpulse = r.linearImpulse;
        j.angularImpulse = r.angularImpulse;
        j.axialImpulse = r.axialImpulse;
        j.lowerImpulse = r.lowerImpulse;
        j.upperImpulse = r.upperImpulse;
    }
}

void JointSolver::move(const Rows& r, SolverBody& a, SolverBody& b, const dvec3& ra, const dvec3& rb, const dvec3& p,
                       const dvec3& l) const
{
    a.movePose(-p, ra);
    b.movePose(p, rb);
    if (l != dvec3(0.0)) {
        a.turnPose(-l);
        b.turnPose(l);
    }
    // RATTLE's pose drifts by its half-step velocity (x1 = x0 + dt v_half), which carries on into
    // the end velocity: a move of the pose is a change of that velocity as large over dt.
    if (!r.rattle)
        return;
    applyLinear(a, b, ra, rb, p / m_settings.dt);
    applyAngular(a, b, l / m_settings.dt);
}

void JointSolver::holdPoints(const Joint& j, const Rows& r, SolverBody& a, SolverBody& b)
{
    const dvec3 ra = glm::mat3_cast(a.endOrientation) * j.localA, rb = glm::mat3_cast(b.endOrientation) * j.localB;
    const dvec3 error = (b.endPosition + rb) - (a.endPosition + ra);
    // RATTLE pushes along the start's rows (r.rA, r.rB): its constraint force is the start's.
    if (r.rattle)
        return move(r, a, b, r.rA, r.rB, -(r.linearMass * error), dvec3(0.0));
    move(r, a, b, ra, rb, -(inverseOr0(pointMass(a, b, ra, rb)) * error), dvec3(0.0));
}

namespace {

/// The position pass's angular move l (A by -l, B by +l), with the move of the anchors that
/// keeps them where they were, as the velocity rows carry them.
void turnCarried(const Joint& j, SolverBody& a, SolverBody& b, const Carried& carried, const dvec3& l)
{
    const dvec3 ra = glm::mat3_cast(a.endOrientation) * j.localA, rb = glm::mat3_cast(b.endOrientation) * j.localB;
    a.turnPose(-l);
    b.turnPose(l);
    const dvec3 p = carried.carry * l;
    a.movePose(-p, ra);
    b.movePose(p, rb);
}

/// carriedWith at the end poses' arms.
Carried carriedAtEnd(const Joint& j, const SolverBody& a, const SolverBody& b)
{
    return carriedWith(a, b, glm::mat3_cast(a.endOrientation) * j.localA, glm::mat3_cast(b.endOrientation) * j.localB);
}

/// A relative turn of B from A (as the velocity rows' spin), with the anchors' gap along the
/// carry (carriedSpin's reason).
dvec3 carriedTurn(const Joint& j, const SolverBody& a, const SolverBody& b, const dmat3& carry, const dvec3& turn)
{
    const dvec3 ra = glm::mat3_cast(a.endOrientation) * j.localA, rb = glm::mat3_cast(b.endOrientation) * j.localB;
    return turn + glm::transpose(carry) * ((b.endPosition + rb) - (a.endPosition + ra));
}

} // namespace

std::pair<dvec3, dvec3> JointSolver::endAxes(const Joint& j, const SolverBody& a, const SolverBody& b)
{
    return {glm::normalize(glm::mat3_cast(a.endOrientation) * j.axisA),
            glm::normalize(glm::mat3_cast(b.endOrientation) * j.axisB)};
}

dvec3 JointSolver::weldError(const Joint& j, const SolverBody& a, const SolverBody& b)
{
    dquat error = (a.endOrientation * j.rest) * glm::conjugate(b.endOrientation);
    if (error.w < 0.0)
        error = -error;
    return 2.0 * dvec3(error.x, error.y, error.z);
}

void JointSolver::holdAxis(const Joint& j, const Rows& r, SolverBody& a, SolverBody& b)
{
    const auto [axisA, axisB] = endAxes(j, a, b);
    // B's axis is A's turned by about axisA x axisB: turn B back by that much, across the axis.
    if (r.rattle) { // along the start's rows (holdPoints); no limits
        const Block2 mass{{{r.acrossMass[0][0], r.acrossMass[0][1]}, {r.acrossMass[1][0], r.acrossMass[1][1]}}};
        const dvec3 l = acrossImpulse(mass, r.across, carriedTurn(j, a, b, r.carry, glm::cross(axisA, axisB)));
        return move(r, a, b, r.rA, r.rB, r.carry * l, l);
    }
    dvec3 across[2];
    acrossOf(axisA, across);
    const Carried carried = carriedAtEnd(j, a, b);
    const dvec3 l = acrossImpulse(inverse2(carried.spin, across), across,
                                  carriedTurn(j, a, b, carried.carry, glm::cross(axisA, axisB)));
    turnCarried(j, a, b, carried, l);
    if (!j.limited)
        return;
    const double angle = hingeAngle(j, a.endOrientation, b.endOrientation);
    const double beyond = angle < j.lower ? angle - j.lower : angle > j.upper ? angle - j.upper : 0.0;
    const double k = glm::dot(axisA, carried.spin * axisA);
    if (beyond != 0.0 && k > 0.0) { // A turns back within the range, B the other way
        const double past = beyond - glm::dot(axisA, carriedTurn(j, a, b, carried.carry, dvec3(0.0)));
        turnCarried(j, a, b, carried, (past / k) * axisA);
    }
}

void JointSolver::holdOrientation(const Joint& j, const Rows& r, SolverBody& a, SolverBody& b)
{
    const dvec3 theta = weldError(j, a, b);
    if (r.rattle) { // along the start's rows (holdPoints)
        const dvec3 l = -(r.angularMass * carriedTurn(j, a, b, r.carry, -theta));
        return move(r, a, b, r.rA, r.rB, r.carry * l, l);
    }
    const Carried carried = carriedAtEnd(j, a, b);
    turnCarried(j, a, b, carried, -(inverseOr0(carried.spin) * carriedTurn(j, a, b, carried.carry, -theta)));
}

void JointSolver::holdLength(const Joint& j, const Rows& r, SolverBody& a, SolverBody& b)
{
    if (j.stiffness > 0.0)
        return; // a spring may stretch
    const dvec3 ra = glm::mat3_cast(a.endOrientation) * j.localA, rb = glm::mat3_cast(b.endOrientation) * j.localB;
    const dvec3 d = (b.endPosition + rb) - (a.endPosition + ra);
    const double len = glm::length(d);
    if (len == 0.0)
        return;
    const dvec3 n = d / len;
    // Along the start's line under RATTLE (holdPoints), the end's otherwise; the length's rate
    // along it is n . K along.
    const dvec3 along = r.rattle ? r.n : n;
    const dvec3 armA = r.rattle ? r.rA : ra, armB = r.rattle ? r.rB : rb;
    const double k = glm::dot(n, pointMass(a, b, armA, armB) * along);
    if (!(k > 0.0))
        return;
    move(r, a, b, armA, armB, (-(len - j.length) / k) * along, dvec3(0.0));
}

void JointSolver::solvePositions()
{
    for (const Rows& r : m_rows) {
        const Joint& j = m_joints[r.joint];
        SolverBody& a = m_bodies[r.a];
        SolverBody& b = m_bodies[r.b];
        switch (j.type) {
        case JointType::Ball: holdPoints(j, r, a, b); break;
        case JointType::Hinge:
            holdAxis(j, r, a, b);
            holdPoints(j, r, a, b);
            break;
        case JointType::Fixed:
            holdOrientation(j, r, a, b);
            holdPoints(j, r, a, b);
            break;
        case JointType::Distance: holdLength(j, r, a, b); break;
        }
    }
}

void JointSolver::projectAtEnd(int sweeps)
{
    m_endRows.clear();
    for (const Rows& r : m_rows) {
        if (!r.rattle)
            continue;
        // RATTLE's first half-kick took half the step's joint impulses (its pose drifted by
        // half of them): the end velocity keeps that half, and the end's projection adds its own.
        SolverBody& a = m_bodies[r.a];
        SolverBody& b = m_bodies[r.b];
        const Joint& j = m_joints[r.joint];
        const dvec3 linear = j.type == JointType::Distance ? r.axialImpulse * r.n : r.linearImpulse;
        applyLinear(a, b, r.rA, r.rB, -0.5 * linear);
        applyAngular(a, b, -0.5 * r.angularImpulse);
        m_endRows.push_back(rowsAt(r.joint, Pose::End));
    }
    for (int it = 0; it < sweeps && !m_endRows.empty(); ++it)
        sweep(m_endRows, false);
    solveExactly(m_endRows);
}

} // namespace pba::rigid

namespace pba {

std::string_view jointTypeName(JointType type)
{
    switch (type) {
    case JointType::Ball: return "ball";
    case JointType::Hinge: return "hinge";
    case JointType::Distance: return "distance";
    case JointType::Fixed: return "fixed";
    }
    return "ball";
}

std::optional<JointType> jointTypeFromName(std::string_view name)
{
    for (const JointType t : {JointType::Ball, JointType::Hinge, JointType::Distance, JointType::Fixed})
        if (jointTypeName(t) == name)
            return t;
    return std::nullopt;
}

} // namespace pba
