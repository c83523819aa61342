#pragma once
// The joints' part of the solver: each joint's rows, solved in the same sweeps as the contacts
// (velocities, warm-started from the last step's impulses) and then held on the poses
// (positions, non-linear Gauss-Seidel), so that a pendulum's rod neither stretches nor adds
// energy. Ball: the two anchors' relative velocity, three rows at once (a 3x3 block). Hinge: the
// ball's rows, two angular rows that keep the axes parallel and, with limits, one that keeps the
// angle in range. Distance: one row along the two anchors, rigid or (with a stiffness) a soft
// constraint, which is an implicit spring (Catto, "Soft Constraints", GDC 2011). Fixed: the
// ball's rows and three angular rows. An angular row carries the anchors along (a linear impulse
// with its angular one), so that it turns the pair about the joint, not each body about its own
// centre: a small ball hinged a metre away is stopped by its limit in one sweep, where alone the
// row spun the ball in place and the ball's rows undid it, a two-hundred-fiftieth a sweep.
//
// A joint that is an equality (a ball joint, a hinge without limits, a weld, a rod) between
// bodies that take velocity Verlet's kind of step is RATTLE (Andersen 1983): its position pass
// pushes along the step's start rows and moves the velocities with the poses, the velocity pass's
// impulses count half, and the velocities are projected onto the joint at the end poses. Its
// energy is then kept to second order in dt (the double-pendulum scene loses 2e-4 of it in 30 s,
// the island's energy cap taking what rounds above), where moving the poses alone took it at
// first order.
#include <functional>
#include <span>
#include <utility>
#include <vector>

#include "pba/joint.hpp"
#include "rigid/contact.hpp"
#include "rigid/contact_solver.hpp"
#include "rigid/solver_body.hpp"

namespace pba::rigid {

/// A joint's end that is the world rather than a body.
inline constexpr BodyIndex kWorldBody = 0xfffffffeu;

struct Joint {
    JointType type = JointType::Ball;
    BodyIndex a = 0, b = 0;       ///< the rigid system's bodies; b may be kWorldBody
    dvec3 localA{0.0}, localB{0.0}; ///< the anchors in each body's frame
    dvec3 axisA{0.0}, axisB{0.0};   ///< hinge: the axis in each body's frame
    dvec3 refA{0.0}, refB{0.0};     ///< hinge: a unit vector across the axis, the same at the start
    dquat rest{1.0, 0.0, 0.0, 0.0}; ///< fixed: A's orientation to B's at the start, qA^-1 qB
    double length = 0.0;            ///< distance
    double stiffness = 0.0;         ///< distance: 0 for a rigid rod
    double damping = 0.0;
    bool limited = false;
    double lower = 0.0, upper = 0.0;
    bool collide = false; ///< two bodies: they collide with each other too
    // What the last step's solve ended with (warm start).
    dvec3 linearImpulse{0.0};
    dvec3 angularImpulse{0.0};
    double axialImpulse = 0.0;  ///< distance
    double lowerImpulse = 0.0, upperImpulse = 0.0;
};

/// The hinge's angle: how far A has turned about the axis relative to B (or the world) since
/// the start, right-handed about the axis.
double hingeAngle(const Joint& j, const dquat& qa, const dquat& qb);

class JointSolver {
public:
    /// `world` is the solver's index of the world's static body.
    void prepare(std::span<Joint> joints, std::span<const std::uint32_t> island, std::span<SolverBody> bodies,
                 const SolverSettings& settings, BodyIndex world);
    void warmStart();
    void solveVelocities();
    /// The collision pass's: between beginBlows and endBlows, sweepBlow solves the joints with
    /// the blow's impulses, from impulses of nothing (a spring passes no blow: it is left out),
    /// and endBlows puts back what the step's sweeps warm-start from.
    void beginBlows();
    void sweepBlow();
    void endBlows();
    /// The moving bodies the joints join, each once.
    std::span<const BodyIndex> bodies() const { return m_movingBodies; }
    /// The pinned bodies among them (Pin), worked out by beginBlows.
    std::span<const Pin> pins() const { return m_pins; }
    /// A hinge this close to a limit (rad) is not pinned: its limit rows act in the blow.
    static constexpr double kPinLimitGap = 0.05;
    /// A blow's mechanism (between beginBlows and endBlows): the moving bodies joined to x or y,
    /// but pinned ones, through joints that pass a blow (not springs), and those joints' rows:
    /// `equalities` keep each joint's relative velocities as they were before the blows, and
    /// `limits` (a hinge's) may only push, as far as the step's gap to the limit. False, with
    /// nothing, where the blow keeps the sweeps: no such body, a particle among them (it has no
    /// turn to take), or more than kMaxMechanismRows rows.
    bool mechanismRows(BodyIndex x, BodyIndex y, std::vector<BodyIndex>& bodies, std::vector<BlowRow>& equalities,
                       std::vector<BlowRow>& limits) const;
    /// The exact blow's matrix is dense: a chain of twelve hinges has 60 rows.
    static constexpr std::size_t kMaxMechanismRows = 72;
    void storeImpulses();
    /// Whether a joint joins two moving bodies over kFarLighter times apart in mass (with at most
    /// kMaxMechanismRows rows in all): the sweeps pass a pull between them at the lighter one's
    /// rate, so that a 50 kg ball on two 0.1 kg links stretched them by a centimetre and came
    /// apart at 1/60 s. Then the joints' rows (but springs') are also solved together exactly
    /// (exact_joints.cpp): at the end of the velocity pass, after the position pass, and after
    /// RATTLE's projection at the end poses.
    bool farApart() const { return m_farApart; }
    /// The velocity rows' impulses, all at once, so that every joint's relative velocity is what
    /// its rows ask (a hinge's limits as inequalities).
    void solveVelocitiesExactly() { solveExactly(m_rows); }
    /// What the room does to body k at its end pose: its points beyond a surface, as
    /// collideWithRoom finds them with no margin (none for a point body, which meets the room by
    /// its own rule).
    using RoomAtEnd = std::function<void(BodyIndex, std::vector<Contact>&)>;
    /// Newton steps on the end poses until every joint holds (anchors, rods' lengths, hinges'
    /// axes and limits, welds' turns), all joints at once, and no jointed body is beyond the room.
    void holdExactly(const RoomAtEnd& room);
    /// The kinetic energy that the explicit springs' impulses (all of a spring between forward
    /// Euler's bodies, taken at the step's start) give the free step's velocities: the method's
    /// own work, as its gain in a fall is, which an island's energy cap must leave to it.
    double explicitSpringWork() const;
    /// One sweep on the bodies' end poses.
    void solvePositions();
    /// After the position pass, RATTLE's end for its joints (velocity Verlet's bodies, and RK4's
    /// and the splitting's, whose end poses drift by the mean velocity too): the velocity pass's
    /// impulses count half, and `sweeps` sweeps project the velocities onto the joints at the
    /// end poses.
    void projectAtEnd(int sweeps);

private:
    struct Rows {
        std::uint32_t joint = 0;
        BodyIndex a = 0, b = 0;
        dvec3 rA{0.0}, rB{0.0};
        dmat3 linearMass{0.0};   ///< K^-1 of the anchors' relative velocity
        dmat3 angularMass{0.0};  ///< fixed: the relative spin's K^-1 (anchors carried along)
        /// hinge, fixed: the linear impulse that goes with an angular one, so that the anchors'
        /// relative velocity stays as it was (carriedWith)
        dmat3 carry{0.0};
        double acrossMass[2][2] = {{0.0, 0.0}, {0.0, 0.0}}; ///< hinge: on the two directions across the axis
        dvec3 axis{0.0}, across[2]{dvec3(0.0), dvec3(0.0)};
        double axialMass = 0.0;  ///< hinge limits: about the axis; distance: along n
        dvec3 n{0.0};            ///< distance: from A's anchor to B's
        double angle = 0.0;      ///< hinge: at the start of the step
        // A distance spring's terms (prepareSpring).
        /// k times the share of its impulse taken at the end of the step, times |d0 + d1| /
        /// (|d0| + |d1|) under a Verlet-type method
        double endStiffness = 0.0;
        double startImpulse = 0.0;  ///< the rest, from the start's stretch, along n
        dvec3 endLine{0.0};         ///< the line between the anchors at the end, as foreseen
        double springStretch = 0.0; ///< the stretch at the end but for dt e . (wB vB - wA vA)
        double springGain = 0.0;    ///< 1 / (1 + dt (endStiffness dt Kw + c K))
        dvec3 linearImpulse{0.0}, angularImpulse{0.0};
        double axialImpulse = 0.0, lowerImpulse = 0.0, upperImpulse = 0.0;
        /// Solved as RATTLE: an equality between velocity Verlet's kind of bodies
        bool rattle = false;
        /// Between beginBlows and endBlows: the anchors' relative velocity and B's spin less A's
        /// before the blows, which the rows keep (zero otherwise)
        dvec3 blowAnchor{0.0}, blowSpin{0.0};
        /// Between beginBlows and endBlows: hinge limits' spin (A's relative to B about the axis,
        /// as the rows measure it) before the blows
        double blowAxialSpin = 0.0;
    };
    void solveBall(Rows& r, SolverBody& a, SolverBody& b);
    /// An angular impulse l (A: -l, B: +l) with the linear impulse its row carries.
    static void applyCarried(Rows& r, SolverBody& a, SolverBody& b, const dvec3& l);
    /// B's spin relative to A's as the angular rows solve for it (carried along the anchors).
    static dvec3 carriedSpin(const Rows& r, const SolverBody& a, const SolverBody& b);
    /// The anchors' relative velocity as the rows solve for it (less blowAnchor).
    static dvec3 rowAnchorVelocity(const Rows& r, const SolverBody& a, const SolverBody& b);
    void solveHingeAngular(const Joint& j, Rows& r, SolverBody& a, SolverBody& b);
    void solveFixedAngular(Rows& r, SolverBody& a, SolverBody& b);
    void solveDistance(const Joint& j, Rows& r, SolverBody& a, SolverBody& b);
    static void prepareSpring(const Joint& j, Rows& r, const SolverBody& a, const SolverBody& b, const dvec3& d,
                              double dt);
    enum class Pose { Start, End };
    /// Joint `index`'s rows at the bodies' start or end poses, with no impulses yet.
    Rows rowsAt(std::uint32_t index, Pose pose) const;
    /// The position pass's move of a joint's bodies by the linear impulse p at the arms and the
    /// angular l (A by -p and -l, B by +p and +l), and for a RATTLE row their velocities as far
    /// again in a step.
    void move(const Rows& r, SolverBody& a, SolverBody& b, const dvec3& ra, const dvec3& rb, const dvec3& p,
              const dvec3& l) const;
    /// The position errors at the end poses that the sweeps and the exact hold both undo: the
    /// hinge's axes, A's and B's in the world (B's is A's turned by about their cross product),
    /// and the rotation that takes B to where A's orientation and a weld's rest put it.
    static std::pair<dvec3, dvec3> endAxes(const Joint& j, const SolverBody& a, const SolverBody& b);
    static dvec3 weldError(const Joint& j, const SolverBody& a, const SolverBody& b);
    void holdPoints(const Joint& j, const Rows& r, SolverBody& a, SolverBody& b);
    void holdAxis(const Joint& j, const Rows& r, SolverBody& a, SolverBody& b);
    void holdOrientation(const Joint& j, const Rows& r, SolverBody& a, SolverBody& b);
    void holdLength(const Joint& j, const Rows& r, SolverBody& a, SolverBody& b);

    std::span<Joint> m_joints;
    std::span<SolverBody> m_bodies;
    SolverSettings m_settings;
    std::vector<Rows> m_rows;
    std::vector<Rows> m_rowsBeforeBlows; ///< beginBlows'
    std::vector<Rows> m_endRows;         ///< projectAtEnd's
    BodyIndex m_world = 0;
    bool m_inBlows = false;
    std::vector<BodyIndex> m_movingBodies;
    bool m_farApart = false;
    /// One row of the exact solves: a BlowRow, and where its impulse goes among `rows`.
    struct ExactRow;
    /// `rows`' rows into `out`, the equalities first; returns how many those are.
    std::size_t exactRowsOf(std::span<const Rows> rows, std::vector<ExactRow>& out) const;
    void solveExactly(std::vector<Rows>& rows);
    /// One row of holdExactly's: a BlowRow, the error along it at the end poses, and its joint's
    /// rows (none for the room's).
    struct GapRow;
    /// The joints' errors at the end poses as rows: their equalities into `gaps` (the anchors'
    /// gap or a rod's length, a hinge's axes apart, a weld's turn), the hinge limits passed into
    /// `limits`. Returns the largest error.
    double endErrorRows(std::vector<GapRow>& gaps, std::vector<GapRow>& limits) const;
    /// The moving bodies' points beyond the room at the end poses, as rows into `limits`.
    /// Returns the deepest.
    double roomRows(const RoomAtEnd& room, std::vector<GapRow>& limits) const;
    /// holdExactly's moves x along `rows` (each with its BlowRow `row` and its joint's `rows`).
    template <class GapRows>
    void moveTogether(const GapRows& rows, std::span<const double> x);
    std::vector<Pin> m_pins;
    void findPins();
    /// mechanismRows' parts: the mechanism's bodies and its joints (`taken`, by row), false for
    /// none or one with a particle; one joint's blow rows.
    bool mechanismOf(BodyIndex x, BodyIndex y, std::vector<BodyIndex>& bodies, std::vector<char>& taken) const;
    void blowRowsOf(const Rows& r, std::vector<BlowRow>& equalities, std::vector<BlowRow>& limits) const;
    /// One sweep of `rows`' velocity rows; with `blow`, not a spring's.
    void sweep(std::vector<Rows>& rows, bool blow);
};

} // namespace pba::rigid
