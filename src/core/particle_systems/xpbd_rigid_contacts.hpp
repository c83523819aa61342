#pragma once
// Rigid bodies as XPBD's substeps meet them (Macklin et al., "Small Steps in Physics
// Simulation"; Müller et al., "Detailed Rigid Body Simulation with Extended Position Based
// Dynamics"): each body near a rope or cloth stepped with XPBD moves along with the substeps (its
// acceleration of the last step, its velocity and spin), a member with a radius found inside it
// after a substep's projections is put back on its surface, its move along it cut by up to mu
// times the depth (Coulomb friction in position, as the room's), one that arrived faster than
// resting contact leaves at e times its speed towards the body (e the larger restitution, as
// between bodies), and the body takes the opposite of what that gave the member (m dx / h, and
// m dv for a bounce) as an impulse at the contact point before the next substep. The bodies' own
// step then starts from their velocities with the step's impulses added.
//
// Met only after the step, by the rigid contact solver, the two sides were staggered: the solver
// saw each particle as a lone ball and the springs answered a step later, which threw a 5 kg crate
// off an XPBD trampoline at dt = 0.002 s (and a 20 kg one at 0.001 s).
//
// A member joined to a body by a ball or a rigid distance joint is held to it in every substep,
// as XPBD holds two bodies (Müller et al.): the member's point and the body's put back the joint's
// distance apart, each moved by its share of the inverse masses along the line between them (the
// body's through its arm and inertia), and the body's velocity and spin changed by its move over h;
// a spring joint as XPBD's springs are (xpbd.hpp), of compliance 1 / k. Held only after the step
// by the joint solver, the rope's end swung free through the substeps and was snapped back once a
// step:
// an XPBD rope holding a 20 kg crate gained energy from dt = 0.005 s and blew up at 1/60 s. With
// the body's share given as an impulse for the next substep instead of moved, a box at rest on a
// rope of one substep bobbed and gained energy. The joint solver after the step then finds the
// joint held. Private to the core.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "contact/narrow_phase.hpp"
#include "pba/math.hpp"
#include "particle_systems/xpbd.hpp"

namespace pba {
class RigidBody;
}

namespace pba::detail {

class XpbdRigidContacts final : public Xpbd::Obstacles {
public:
    /// The members: each one's world index, state, radius, mass and friction (a member without a
    /// radius meets nothing).
    struct Members {
        std::span<const std::size_t> world;
        std::span<const dvec3> x, v;
        std::span<const double> radius, mass, friction, restitution;
    };
    /// A joint between a particle and a rigid body (world indices): the particle's point (its
    /// position plus `offset`: a particle does not turn) and the body's (`local`, in its frame)
    /// kept `length` apart (0 for a ball joint), rigidly or, with a stiffness (N/m), as a spring
    /// with its damping (N s/m). The two never touch unless the joint says they `collide`.
    struct Joint {
        std::size_t particle = 0, body = 0;
        dvec3 offset{0.0}, local{0.0};
        double length = 0.0, stiffness = 0.0, damping = 0.0;
        bool collide = false;
    };
    /// The rigid bodies (world index, body) that the members may meet in a step of dt: those
    /// whose bounding spheres, moving, come near the members' box, and those joined to a member.
    void begin(std::span<const std::pair<std::size_t, const RigidBody*>> bodies, const Members& members,
               std::span<const Joint> joints, double dt);
    bool empty() const { return m_bodies.empty(); }

    void advance(double h) override;
    void hold(std::span<dvec3> x, std::span<const dvec3> start) override;
    void keepOut(std::size_t p, const dvec3& start, dvec3& x) override;
    bool bounce(std::size_t p, const dvec3& arriving, double resting, dvec3& v) override;
    void react() override;

    /// What the step's substeps gave each body met: (world index, impulse, angular impulse about
    /// its centre).
    struct Reaction {
        std::size_t body = 0;
        dvec3 impulse{0.0}, moment{0.0};
    };
    std::vector<Reaction> reactions() const;

private:
    struct Body {
        std::size_t world = 0;
        const contact::CollisionShape* shape = nullptr;
        dvec3 x{0.0}, v{0.0}, accel{0.0}, momentum{0.0};
        dquat q{1.0, 0.0, 0.0, 0.0};
        double inverseMass = 0.0;
        dmat3 inverseInertiaBody{0.0};
        double friction = 0.0, restitution = 0.0, reach = 0.0;
        dvec3 impulse{0.0}, moment{0.0}; ///< the step's, in all
        dvec3 spin() const;
    };
    /// What one member did to one body in the substep.
    struct Push {
        std::uint32_t body = 0;
        dvec3 impulse{0.0}, moment{0.0};
    };
    /// The body a member was last put back out of in the substep: the normal (from the member
    /// into the body) and the arm to the contact point.
    struct Touch {
        std::uint32_t body = kNone;
        dvec3 normal{0.0}, arm{0.0};
    };
    static constexpr std::uint32_t kNone = 0xffffffffu;
    /// A joint as the substeps hold it: its member and body (an index into m_bodies), and a
    /// spring's multiplier over the substep's sweeps so far.
    struct Held {
        std::uint32_t member = 0, body = 0;
        Joint joint;
        double lambda = 0.0;
    };
    /// Bodies' spheres in a hashed grid of cells (Müller's "Ten Minute Physics" hashing): a
    /// body is listed in each cell its sphere overlaps, and a member looks only at the bodies
    /// listed in its own cell. A sheet over a bed of 1,600 fixed blocks spent most of its time
    /// testing each of its balls against each block, every substep.
    class SphereGrid {
    public:
        struct Sphere {
            std::uint32_t body = 0;
            dvec3 centre{0.0};
            double radius = 0.0;
        };
        /// `spheres` in increasing body order; each cell's list keeps that order.
        void build(double cell, std::span<const Sphere> spheres);
        void clear() { m_bodies.clear(); }
        /// The bodies listed in x's cell (with those of any cell sharing its bucket), in order.
        std::span<const std::uint32_t> near(const dvec3& x) const;

    private:
        double m_cell = 1.0;
        std::uint32_t m_mask = 0;
        std::vector<std::uint32_t> m_start;  ///< bucket b's bodies: m_bodies[start[b], start[b + 1])
        std::vector<std::uint32_t> m_bodies;
        std::vector<std::uint32_t> m_last;   ///< per bucket, the last body counted into it
        std::vector<std::uint32_t> m_fill;
    };
    /// Sorts the bodies met this step into those every member looks at (all of them when they
    /// are few; else the ones wider than a few cells), the fixed ones' grid, built now, and the
    /// moving ones, gridded in each substep where they are then.
    void sortBodies();
    void gridMovingBodies();
    /// Calls f(k) for every body k that may touch a member at x, in increasing k: the order a
    /// test of every body would meet them in, so the pushes and the states are the same.
    template <class F>
    void forEachNear(const dvec3& x, F&& f) const;
    std::vector<Body> m_bodies;
    double m_cell = 1.0;
    double m_margin = 0.0; ///< what a body's sphere is grown by: two of the largest member radii
    std::vector<std::uint32_t> m_always;  ///< bodies every member looks at, in order
    std::vector<std::uint32_t> m_moving;  ///< the gridded moving bodies, in order
    SphereGrid m_fixedGrid, m_movingGrid;
    std::vector<SphereGrid::Sphere> m_spheres; ///< scratch for the grids
    std::span<const double> m_radius, m_mass, m_friction, m_restitution;
    double m_h = 0.0;
    std::vector<std::vector<Push>> m_pushes; ///< per member, this substep's
    std::vector<Touch> m_touch;              ///< per member, this substep's
    std::vector<std::pair<std::uint32_t, std::uint32_t>> m_joined; ///< (member, body) pairs a joint joins, in order
    std::vector<Held> m_held;
};

} // namespace pba::detail
