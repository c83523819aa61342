#pragma once
// Extended position-based dynamics (Macklin, Mueller and Chentanez, "XPBD", 2016) in small steps
// (Macklin et al., "Small Steps in Physics Simulation", 2019): each spring of stiffness k is a
// distance constraint C = |x_b - x_a| - L of compliance 1/k, and a step of dt is `substeps`
// substeps of h = dt / substeps, each
//     v += h a_ext(x, v),  x* = x + h v,  one projection of every constraint,  v = (x* - x) / h,
// with a_ext every force but the springs. A rope's or cloth's bending springs (across two links)
// are distance constraints too, so the same scene runs with either family of methods.
//
// One projection (lambda starting at zero in every substep, as Small Steps has it) moves the ends
// by dl = (-C - gamma grad C . (x* - x)) / ((1 + gamma) (w_a + w_b) + 1 / (k h^2)) along the
// spring, gamma = c / (k h) the spring's damping c as XPBD's constraint damping. For one spring
// this is backward Euler at h exactly (tested); as the substeps grow it converges to the springs'
// motion, and with k -> infinity to the stiff limit, the constraint held exactly.
//
// One sweep a substep suffices while each constraint's compliance 1 / (k h^2) outweighs its ends'
// inverse masses, (w_a + w_b) k h^2 small: a correction then barely moves the neighbours' errors.
// A stiff chain at a long substep is the opposite case: one sweep moves the error a link or two
// along the chain, and the rest is left as stretch (the rope at 100 times semi-implicit Euler's
// limit, (w_a + w_b) k h^2 = 196, was left four times its length, its energy 45 times the start's).
// There the substep sweeps again, each sweep with the multipliers lambda accumulated (XPBD's
// -alpha~ lambda term), until every constraint's error is under kTolerance of its rest length:
// converged, the substep is backward Euler's, which loses energy.
//
// The room is a constraint of every substep too (Small Steps' ground contacts): after the springs'
// projection a member beyond one of its surfaces is put back on it, its move along the surface
// in the substep cut by up to mu times the depth it was put back by (Coulomb friction in
// position: static while the move is within it), and a member that arrived faster than two
// substeps of its acceleration leaves at e times its speed of arrival (a bounce). A sheet lying
// on the floor then rests on it within the step; with the room only after the step, the springs
// and gravity pulled it in every step for the rule after it to push back (a bounce a step). The
// rigid bodies are met in every substep the same way, both ways (Obstacles,
// xpbd_rigid_contacts.hpp), and so are the members with a radius, each other (Touching, found
// once a step; the contacts after the step then find them apart): met only after the step, the
// upper layers of a sheet lying in folds stirred on the lower ones for as long as it lay.
//
// The constraints are projected Gauss-Seidel, colour by colour: a greedy colouring, in the
// springs' order, puts no two springs that share a body in one colour, so the springs of a colour
// are projected at once on all cores and the result is the same on any number of threads.
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "pba/collision.hpp"
#include "pba/math.hpp"

#include "particle_systems/spring_system.hpp"

namespace pba::detail {

/// What Coulomb friction in position takes back of a move across a surface of normal n, pressed
/// `depth` into it: the move's part along the surface, all of it or mu times the depth of it.
inline dvec3 heldBack(const dvec3& moved, const dvec3& n, double mu, double depth)
{
    const dvec3 along = moved - glm::dot(moved, n) * n;
    const double length = glm::length(along), held = mu * depth;
    return length > 0.0 ? (length <= held ? 1.0 : held / length) * along : dvec3(0.0);
}

class Xpbd {
public:
    /// What moves the bodies besides the springs: fills accel[k] for member k at (x, v).
    using External = std::function<void(std::span<const dvec3> x, std::span<const dvec3> v, std::span<dvec3> accel)>;
    /// What each substep keeps the members out of besides the room, moving along (the rigid
    /// bodies, xpbd_rigid_contacts.hpp).
    class Obstacles {
    public:
        virtual ~Obstacles() = default;
        /// Before a substep's projections: the obstacles move on by h.
        virtual void advance(double h) = 0;
        /// After them (after each sweep of them): the members joined to obstacles held to them,
        /// one joint after another (a body may hold several members), both sides moved; `start`
        /// where the members began the substep.
        virtual void hold(std::span<dvec3> x, std::span<const dvec3> start) = 0;
        /// After them: member p, at x, having begun the substep at `start`, put back outside every
        /// obstacle (on all cores, each member by itself).
        virtual void keepOut(std::size_t p, const dvec3& start, dvec3& x) = 0;
        /// Then, its velocity v made from its move: whether it bounced off an obstacle it arrived
        /// at faster than `resting` (with the velocity `arriving`), v changed if so.
        virtual bool bounce(std::size_t p, const dvec3& arriving, double resting, dvec3& v) = 0;
        /// Then what the members did to the obstacles in the substep, given to them.
        virtual void react() = 0;
    };
    /// Two members that may touch in the step (balls whose centres stay `reach` apart), and their
    /// contact's friction.
    struct Touching {
        std::uint32_t a = 0, b = 0;
        double reach = 0.0, friction = 0.0;
    };
    /// The room each substep keeps the members in: its surfaces (met by a member's centre inflated
    /// by its radius), and per member its radius, restitution and friction; and what else: the
    /// members that may touch each other, and the obstacles.
    struct Room {
        std::span<const Plane> planes;
        std::span<const double> radius, restitution, friction;
        std::span<const Touching> touching;
        Obstacles* obstacles = nullptr; ///< none when null
    };

    Xpbd() = default;
    /// Colours `springs` for the projections.
    explicit Xpbd(const SpringSystem& springs);

    /// One step of dt in `substeps` substeps; x and v (one per member) from the start to the end.
    /// The springs' fixed ends must be placed.
    void step(const SpringSystem& springs, std::span<const double> mass, std::span<dvec3> x, std::span<dvec3> v,
              double dt, int substeps, const External& external, const Room& room);

    /// The last step's bounces of member k off the room and the obstacles (arrivals faster than
    /// resting contact).
    int bounces(std::size_t k) const { return m_bounces.empty() ? 0 : m_bounces[k]; }

    /// Above this (w_a + w_b) k h^2 for some constraint, a substep sweeps until every error is
    /// below kTolerance of its rest length, or kMaxSweeps times.
    static constexpr double kStiff = 0.3;
    static constexpr double kTolerance = 1e-2;
    static constexpr int kMaxSweeps = 1000;

    std::size_t colours() const { return m_colourStart.empty() ? 0 : m_colourStart.size() - 1; }

private:
    /// A spring as a constraint, stored colour by colour so that a colour's pass reads its
    /// constraints in order (the springs' own arrays, read through a colour's list of indices,
    /// were a cache miss a spring).
    struct Constraint {
        std::uint32_t a = 0, b = 0; ///< b == SpringSystem::kFixed: fixed at the spring's fixed point
        std::uint32_t spring = 0;   ///< the spring's index, for its fixed point
        double restLength = 0.0;
        double inverseStiffness = 0.0;     ///< 1 / k, the compliance; negative: no stiffness, no constraint
        double dampingOverStiffness = 0.0; ///< c / k
    };
    /// What a projection reads, the same in every substep of a step, one record per constraint in
    /// colour order and nothing else, since the sweep streams them: the ends, the rest length,
    /// each end's share of the correction, w / ((1 + gamma) (w_a + w_b) + 1 / (k h^2)), and gamma.
    /// (A spring of no stiffness has shares of zero: its projection moves nothing.)
    struct Projection {
        std::uint32_t a = 0, b = 0; ///< b == SpringSystem::kFixed: fixed at the spring's fixed point
        double restLength = 0.0, shareA = 0.0, shareB = 0.0, gamma = 0.0;
    };
    /// What the repeated sweeps read besides: alpha~ = 1 / (k h^2) and 1 / ((1 + gamma) (w_a + w_b)
    /// + alpha~), zero for a spring of no stiffness.
    struct Multiplier {
        double compliance = 0.0, inverseDenominator = 0.0;
    };
    void scale(double h);
    /// Touching members apart after a substep's projection, with friction, pair after pair.
    void keepApart(std::span<const Touching> touching, std::span<dvec3> x) const;
    /// Member p back inside the room after a substep's projection, with friction; the plane it
    /// was put back on (or -1).
    int keepInRoom(const Room& room, std::size_t p, dvec3& x) const;
    /// One sweep over the constraints. kSweeps: with the multipliers of the substep's earlier
    /// sweeps, returning the largest error it met relative to the rest length (without: 0).
    template <bool kSweeps>
    double project(const SpringSystem& springs, std::span<dvec3> x);

    /// The constraints by colour: m_constraints[m_colourStart[c]] up to m_constraints[m_colourStart[c + 1]].
    std::vector<Constraint> m_constraints;
    std::vector<Projection> m_projections; ///< one per constraint, for the step's h
    std::vector<Multiplier> m_multipliers; ///< one per constraint, for the step's h
    std::vector<std::uint32_t> m_colourStart;
    std::vector<double> m_inverseMass;
    std::vector<dvec3> m_start, m_accel;
    std::vector<double> m_lambda; ///< each constraint's accumulated multiplier in the substep
    std::vector<int> m_bounces;     ///< each member's bounces in the step
    double m_stiffest = 0.0; ///< the largest (w_a + w_b) k h^2 over the constraints, for the step's h
    double m_scaledFor = 0.0; ///< the h the projections were made for (0: not yet)
};

} // namespace pba::detail
