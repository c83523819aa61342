#pragma once
// The contact solver: sequential impulses (Catto's method, as in Box2D and Bullet) over the
// contacts of one island, after every body of it has taken its free step with its own
// integrator. Three passes:
//  1. collisions: each contact whose points arrive faster than a resting speed takes the impulse
//     that sends them off at e times the speed they arrive with, at the time within the step at
//     which they arrive (the velocity before impact, not the start's or the end's), a contact's
//     points together and the contacts one after another, so that a blow passes along a row of
//     touching balls as in Newton's cradle, and a box landing flat leaves flat (in a mechanism
//     the joints are swept with each blow's impulses);
//  2. velocities: every contact, warm-started with the last step's impulses, may close its gap
//     but not cross it (speculative contacts), with Coulomb friction, for a fixed number of
//     sweeps; joints take part here (joint_solver.hpp);
//  3. positions: what overlap remains beyond a slop is pushed apart on the poses alone
//     (non-linear Gauss-Seidel, as Box2D v2.4's position solver), adding no velocity and so no
//     energy.
// Every pass visits the island's contacts in their order (by body pair), on one thread, but for
// the velocity sweeps of a large island, which visit them colour by colour, four at a time
// (wide_contact_rows.hpp), and a huge island's passes, which visit the contacts within each half
// of it at once and then those across the cut (halves.hpp): the result depends on nothing else.
#include <algorithm>
#include <span>
#include <vector>

#include "pba/contact_settings.hpp"
#include "rigid/contact.hpp"
#include "rigid/halves.hpp"
#include "rigid/solver_body.hpp"
#include "rigid/velocity_rows.hpp"
#include "rigid/wide_contact_rows.hpp"

namespace pba::rigid {

class JointSolver;

/// A body over this many times lighter than one it touches or is joined to is far lighter: the
/// sweeps pass a push between the two at the lighter one's rate, so the solver takes their rows
/// exactly as well (exact_normals.cpp, exact_joints.cpp), and a blow meets the lighter held.
inline constexpr double kFarLighter = 20.0;

/// What one step's solve works with: the world's knobs, and what this step makes of them.
struct SolverSettings {
    ContactSettings contact;
    double dt = 0.0;
    /// Below this arriving speed a point does not bounce: one step of gravity's, twice over.
    double restingSpeed = 0.0;
    /// The most one position sweep moves a contact apart (m).
    double maxCorrection = 0.2;
    /// Velocity sweeps: at least contact.velocityIterations, and on while the impulses still
    /// change, up to this many in all.
    int maxVelocityIterations() const { return std::max(contact.velocityIterations, contact.maxVelocityIterations); }
};

/// One contact point as the collision pass sees it, worked out once a step (its masses are an
/// arrival's own rows', found where the point arrives).
struct PointRows {
    dvec3 rA{0.0}, rB{0.0}; ///< arms from each body's centre to the point, world, at the start
    dvec3 n{0.0};           ///< normal, A to B
    dvec3 t[2]{dvec3(0.0), dvec3(0.0)};
    double normalMass = 0.0;
    double tangentMass[2] = {0.0, 0.0};
    double separation = 0.0; ///< at the start of the step
    double vnStart = 0.0;    ///< relative normal speed at the start's velocities
    double vnFree = 0.0;     ///< and at the end of the free step
    double vtStart[2] = {0.0, 0.0};
    double vtFree[2] = {0.0, 0.0};
    bool bounced = false;
};

/// Body B's point's velocity less body A's, at the bodies' present velocities.
inline dvec3 relativeVelocity(const SolverBody& a, const SolverBody& b, const PointRows& r)
{
    return b.pointVelocity(r.rB) - a.pointVelocity(r.rA);
}

/// A row of a blow solved exactly (the collision pass's small LCP): B's point less A's along n,
/// at arms rA and rB, or (angular) B's spin less A's about n; the blow brings that speed to
/// `target` (a joint's row), or to at least it (a contact's).
struct BlowRow {
    BodyIndex a = 0, b = 0;
    dvec3 rA{0.0}, rB{0.0}, n{0.0};
    bool angular = false;
    double target = 0.0;

    double speed(const SolverBody& x, const SolverBody& y) const
    {
        return angular ? glm::dot(n, y.w - x.w) : glm::dot(n, y.pointVelocity(rB) - x.pointVelocity(rA));
    }
    /// The row's impulse lambda: on y along n, on x against it (a blow's linear rows go through
    /// its pins instead: ContactSolver::pushRow).
    void push(SolverBody& x, SolverBody& y, double lambda) const
    {
        if (angular) {
            x.applyAngularImpulse(-lambda * n);
            y.applyAngularImpulse(lambda * n);
            return;
        }
        x.applyImpulse(-lambda * n, rA);
        y.applyImpulse(lambda * n, rB);
    }
};

/// A of w = A x + b over `n` blow rows, row-major: row i's change of speed for a unit push of
/// row j, found by pushing row j and putting its two bodies' velocities back. `rowOf(i)` is row
/// i; `push(row, lambda)` applies a row's impulse (a blow's through the pins).
template <class RowOf, class Push>
void blowRowMatrix(std::span<SolverBody> bodies, std::size_t n, RowOf&& rowOf, Push&& push, std::vector<double>& a)
{
    const auto speed = [&](const BlowRow& row) { return row.speed(bodies[row.a], bodies[row.b]); };
    std::vector<double> now(n);
    for (std::size_t i = 0; i < n; ++i)
        now[i] = speed(rowOf(i));
    a.assign(n * n, 0.0);
    for (std::size_t j = 0; j < n; ++j) {
        const BlowRow& pushed = rowOf(j);
        SolverBody& pa = bodies[pushed.a];
        SolverBody& pb = bodies[pushed.b];
        const dvec3 va = pa.v, wa = pa.w, vb = pb.v, wb = pb.w;
        push(pushed, 1.0);
        for (std::size_t i = 0; i < n; ++i)
            a[i * n + j] = speed(rowOf(i)) - now[i];
        pa.v = va, pa.w = wa, pb.v = vb, pb.w = wb;
    }
}

/// Solves one island's contacts. `contacts` holds every contact of the world; `island` lists
/// the indices of this island's, in order. Works on `bodies` (the world's solver bodies: the
/// island's and the static ones) and writes the impulses back into the contacts.
class ContactSolver {
public:
    /// `moving`: the island's moving bodies; `withJoints`: the caller interleaves a joint
    /// solver's sweeps with these (never halved).
    void prepare(std::span<Contact> contacts, std::span<const std::uint32_t> island,
                 std::span<const std::uint32_t> moving, std::span<SolverBody> bodies, const SolverSettings& settings,
                 bool withJoints = false);
    /// Islands of this many contacts and no joints are halved: a heap of a few hundred dice. A
    /// thousand dice's heap (2,500 contacts) steps 1.06 times as fast in halves; with 8 position
    /// sweeps its landing went deeper than the whole island's, with 16 it does not (7 throws).
    static constexpr std::size_t kHalvedContacts = 512;
    /// Pass 1: restitution at the time of arrival, each contact giving at most `maxStrikes` blows
    /// (kEveryStrike: as many as the sweeps find). Returns whether any point bounced.
    bool collide(int maxStrikes = kEveryStrike);
    /// The same for a mechanism: each blow's impulses are solved with `joints`' sweeps, so that
    /// it meets the bodies as the joints hold them (a ball striking a door near its hinge
    /// rebounds as from the door and its hinge, not from a free door).
    bool collide(JointSolver& joints);
    static constexpr int kEveryStrike = 255;
    /// A heap's: a row of balls passes a blow on with one a contact (Newton's cradle), while a
    /// jammed heap of dice would pass blows back and forth through every contact until the
    /// sweeps run out (a 10,000-dice pile: 28,000 blows a step, nearly 16 sweeps).
    static constexpr int kHeapStrikes = 2;
    /// The collision pass's sweeps at most.
    static constexpr int kMaxCollisionSweeps = 16;
    /// Pass 2: the last step's impulses (of the points that did not bounce), and a large
    /// island's rows packed four contacts to a block; then the sweeps are the caller's,
    /// interleaved with the joints'.
    void warmStart();
    /// One sweep; true when it changed no impulse by more than a millionth of the largest.
    bool solveVelocities();
    /// Passes 1 and 2 for an island without joints: the collisions, the warm start and at least
    /// `least` sweeps, on until one converges, `most` in all; a halved island's on two cores.
    void solveVelocities(int maxStrikes, int least, int most);
    /// The end of pass 2, after the sweeps: where a body touches one far lighter, the normal
    /// impulses solved exactly (exact_normals.cpp); a mechanism's `joints` swept beside friction
    /// between the exact solves (and solved exactly too where they join bodies far apart in
    /// mass). solveVelocities ends with it; a mechanism's caller calls it.
    void finishVelocities(JointSolver* joints = nullptr);
    /// Body k's velocity and spin as the collision pass left them: the velocity pass's
    /// impulses, which act from the start of the step, are what it changed since.
    std::pair<dvec3, dvec3> afterCollisions(BodyIndex k) const { return {m_marks[2 * k], m_marks[2 * k + 1]}; }
    /// Each point's impulses back into its contact, for the next step's warm start.
    void storeImpulses();
    /// Pass 3, on the bodies' end poses; one sweep over `contacts`, found at those poses (what
    /// the step's turning brought into contact is there, which the start's manifolds missed).
    void solvePositions(std::span<const Contact> contacts);
    /// `sweeps` of them (without joints; a halved island's on two cores).
    void solvePositions(std::span<const Contact> contacts, int sweeps);
    /// After the room's push-out has moved the bodies `held`: `sweeps` more over `contacts` (the
    /// last position sweeps' rows, if there were any), with those bodies as fixed as the room, so
    /// that what the push-out lifted them into moves away from them and not back into the room.
    void settleOn(std::span<const Contact> contacts, std::span<const std::uint32_t> held, int sweeps);

private:
    /// A point's two surface points and normal with the bodies at the given poses.
    struct SurfacePoints {
        dvec3 a{0.0}, b{0.0}, n{0.0};
    };
    static SurfacePoints surfacePoints(double radiusA, double radiusB, const ContactPoint& p, const dvec3& xa,
                                       const dmat3& ra, const dvec3& xb, const dmat3& rb);
    /// A point's rows where it arrives, and what the collision pass wants of it.
    struct ImpactRow {
        int point = 0;
        PointRows rows;
        double targetN = 0.0, targetT[2] = {0.0, 0.0};
        double pushN = 0.0, pushT[2] = {0.0, 0.0};
    };
    void solveFriction(const IslandContact& c, SolverBody& a, SolverBody& b, double& change);
    void solveNormal(const IslandContact& c, SolverBody& a, SolverBody& b, double& change, double& largest);
    /// The end of pass 2 in an island where a body touches one far lighter (exact_normals.cpp):
    /// the normal impulses as one exact program, friction (and a mechanism's joints) swept
    /// between such solves.
    bool needsExactNormals() const;
    void solveNormalsExactly(JointSolver* joints);
    static constexpr int kExactRounds = 4; ///< exact solves, a friction sweep between two
    /// Products of the program's matrix a solve at most (three towers of 0.1 and 50 kg boxes in
    /// turn, settling side by side, took about 40 a solve).
    static constexpr int kExactIterations = 3000;
    static constexpr double kExactSpeed = 1e-6; ///< m/s: a row's speed as exact as it need be
    std::vector<std::int32_t> m_exactPlace;      ///< per body: -1 but while the exact rows are built
    /// A contact's blow in the collision pass: when its first point arrives (false: none
    /// does), the rows of the points arriving then, their impulses together.
    bool collideOne(const IslandContact& c);
    bool firstArrival(const IslandContact& c, double& tau, bool (&arrives)[contact::Manifold::kMaxPoints]) const;
    int impactRows(const IslandContact& c, double tau, const bool (&arrives)[contact::Manifold::kMaxPoints],
                   ImpactRow (&rows)[contact::Manifold::kMaxPoints]) const;
    void solveImpact(const IslandContact& c, std::span<ImpactRow> rows);
    /// A point of a pinned body resting on a static one, held in the blow from approaching
    /// faster than it did (no bounce: its own arrival is a blow of its own).
    struct RestingRow {
        BodyIndex a = 0, b = 0;
        PointRows rows;
        double targetN = 0.0, pushN = 0.0;
    };
    /// The resting points of the pinned bodies among c's two, of one of them far lighter than
    /// the other (farLighterIn) and of the blow's mechanism, on static bodies, but those of
    /// `rows`; at most kMaxRestingRows, the closest to touching.
    void restingRows(const IslandContact& c, std::span<const ImpactRow> rows);
    static constexpr std::size_t kMaxRestingRows = 12;
    /// Whether body k of contact c is over kFarLighter times lighter than its moving partner: a
    /// blow of the partner then meets it held by what it rests on (blows passed back and forth,
    /// two a contact, left a 5 kg ball dropped on a 0.1 kg plate on the floor lying on it).
    bool farLighterIn(const IslandContact& c, BodyIndex k) const;
    /// With resting rows or a mechanism: the normal pushes of `rows`, m_resting's and the
    /// mechanism's joint rows together, exactly.
    void solveBlowNormals(const IslandContact& c, std::span<ImpactRow> rows, double& change, double& largest);
    struct NormalRow {
        BlowRow row;
        double* push = nullptr;
    };
    static BlowRow blowRow(BodyIndex a, BodyIndex b, const PointRows& r, double target)
    {
        return {a, b, r.rA, r.rB, r.n, false, target};
    }
    /// The blow's impulse `lambda` along a row.
    void pushRow(const BlowRow& r, double lambda);
    std::vector<NormalRow> m_normals;      ///< solveBlowNormals' scratch
    std::vector<double> m_normalMatrix;    ///< its rows' J M^-1 J^T, made once a blow
    bool m_normalMatrixMade = false;
    /// The present blow's mechanism (JointSolver::mechanismRows), its rows and their pushes.
    std::vector<BodyIndex> m_mechanism;
    std::vector<BlowRow> m_jointEqualities, m_jointLimits;
    std::vector<double> m_jointPushes;
    /// A blow's masses and impulses: a pinned body's (Pin) or a free one's.
    double blowInverseMass(BodyIndex k, const dvec3& r, const dvec3& u) const;
    double blowMass(BodyIndex a, BodyIndex b, const dvec3& ra, const dvec3& rb, const dvec3& u) const;
    void applyBlow(BodyIndex a, BodyIndex b, const dvec3& rA, const dvec3& rB, const dvec3& p);
    void applyBlow(BodyIndex a, BodyIndex b, const PointRows& r, const dvec3& p) { applyBlow(a, b, r.rA, r.rB, p); }
    /// Whether contact k gives a blow now (collide's look at it).
    bool lookForBlow(std::size_t k, int maxStrikes);
    void startCollisions();
    /// The rows of these contacts' points, where their `first` says.
    void prepareRows(std::span<const IslandContact> constraints);
    void warmStart(std::span<const IslandContact> constraints);
    void markVelocities(std::span<const std::uint32_t> bodies);
    /// A halved island's contacts of one part: within one half of its moving bodies, or across.
    struct Part {
        std::span<const IslandContact> constraints; ///< a run of m_constraints, in the island's order
        std::uint32_t first = 0;                  ///< where the run starts in m_constraints
        std::vector<std::uint32_t> bodies;        ///< the half's moving bodies (none across)
        WideContactRows wide;
        std::vector<std::uint32_t> oneAtATime;    ///< indices into constraints
        double change = 0.0, largest = 0.0;       ///< its last sweep's
        bool struck = false;                      ///< its last collision sweep's
    };
    /// Cuts the island's moving bodies in two at the median along its longest extent.
    void halve();
    void sweep(Part& part);
    Part& part(Half half) { return m_parts[std::size_t(half)]; }
    bool m_halved = false;
    Part m_parts[3];
    std::vector<std::int8_t> m_side;           ///< per body: its half, or -1 (static, or not this island's)
    std::vector<std::uint32_t> m_sided;        ///< the bodies m_side holds a half for
    std::vector<std::pair<double, std::uint32_t>> m_along; ///< scratch: the bodies along the cut's axis
    std::vector<IslandContact> m_byPart;       ///< scratch: the contacts put in their parts' runs
    /// One point of the position pass without joints: its arms turned once for all the sweeps.
    struct PositionRow {
        BodyIndex a = 0, b = 0;
        dvec3 n{0.0};
        double radiusA = 0.0, radiusB = 0.0;
        dvec3 armA{0.0}, armB{0.0}; ///< from each centre to the point's anchor on it, world
    };
    /// The points of `contacts` as rows, at the bodies' end orientations, part by part.
    void positionRows(std::span<const Contact> contacts);
    void solvePosition(const PositionRow& row)
    {
        pushApart(row, m_bodies[row.a].inverseMass, m_bodies[row.b].inverseMass);
    }
    /// One row's push, each body moved by its share `wa`, `wb` (its inverse mass, or 0 where held).
    void pushApart(const PositionRow& row, double wa, double wb);
    std::vector<PositionRow> m_positionRows;
    bool m_positionRowsBuilt = false; ///< for this island, since the last turn of its bodies
    std::vector<std::uint8_t> m_held; ///< settleOn's bodies, by index
    std::size_t m_partRows[4] = {0, 0, 0, 0}; ///< part h's rows: [m_partRows[h], m_partRows[h + 1])
    std::span<const std::uint32_t> m_moving;   ///< the island's moving bodies
    std::vector<dvec3> m_marks;                ///< per body: v and w after the collision pass
    double refineArrival(const IslandContact& c, int point, double tPrev, double tau) const;
    double restitutionOf(const IslandContact& c, const PointRows& r) const;

    std::span<Contact> m_contacts;
    std::span<SolverBody> m_bodies;
    SolverSettings m_settings;
    std::vector<IslandContact> m_constraints;
    std::vector<PointRows> m_rows;
    std::vector<VelocityRows> m_velocityRows; ///< the same points', as the sweeps see them
    /// A large island's sweeps: most contacts four at a time, the rest (m_oneAtATime) after.
    WideContactRows m_wide;
    std::vector<std::uint32_t> m_oneAtATime; ///< indices into m_constraints, in order
    JointSolver* m_impactJoints = nullptr; ///< collide(JointSolver&)'s, while it runs
    std::span<const Pin> m_pins;           ///< collide(JointSolver&)'s pinned bodies
    std::vector<std::int32_t> m_pinOf;     ///< per body: its pin in m_pins, or -1
    std::vector<RestingRow> m_resting;     ///< the present blow's
    /// The velocities of the joints' bodies before a blow (collideOne).
    std::vector<std::pair<dvec3, dvec3>> m_jointBodiesBefore;
    std::vector<std::uint32_t> m_blows; ///< the collision pass's: per body, the blows it took
    std::vector<std::uint64_t> m_seen;  ///< per contact, its bodies' blows when last looked at
    std::vector<std::uint8_t> m_strikes; ///< per contact, the blows it gave this step
    double m_change = 0.0, m_largest = 0.0; ///< the last sweep's largest change and impulse
};

/// Two unit vectors that complete n to an orthonormal frame (the same for the same n, bit for bit).
void tangentsOf(const dvec3& n, dvec3 (&t)[2]);

} // namespace pba::rigid
