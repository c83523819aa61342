#pragma once
// The rigid bodies' part of a World: which of the world's bodies are rigid, and what makes them
// touch each other and the room: the broad phase, the narrow phase, the contact cache, the
// islands with their sleep, the contact solver and the joints. The World integrates each awake
// body with its own integrator (its free step, under every force); the system then finds the
// contacts at the start of the step and solves them, island by island, into each body's end.
//
// A step, phase by phase (each a function over the system's own arrays):
//   begin          the bodies' start states, what they are made of, who is awake
//   (the World's free step of the awake bodies, written with setFreeEnd)
//   findContacts   broad phase, narrow phase against bodies and the room, warm start from the
//                  cache, and the sleeping islands an awake body touched, woken
//   (the World's free step of the bodies just woken)
//   solve          islands, then per island: collisions, velocities, positions; then the
//                  nets' segments and triangles against the bodies (piece_contacts.hpp); then sleep
//   (the World writes each end state back into its body)
//
// A particle with a radius (or joined to a rigid body) takes part as a point body: a ball that
// does not turn, its start and free end states the particle's own step's (setPoint), touching
// rigid bodies both ways with the same contact rule and joined to them by the same joints. It
// meets the room with the particle's own rule and other particles not here, and never sleeps.
// A particle stepped by XPBD meets the rigid bodies inside its substeps instead
// (xpbd_rigid_contacts.hpp): here it is only joined, and the bodies it pushed are kept awake. One
// stepped by implicit Euler that rests on a body (its contact here of the last step) is held on
// it within its own solve (backward_euler.hpp's bearers), whose pushes the World gives the body
// at the end of its free step.
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "contact/narrow_phase.hpp"
#include "pba/collision.hpp"
#include "pba/contact_settings.hpp"
#include "pba/integrator.hpp"
#include "pba/rigid_body.hpp"
#include "pba/rotation.hpp"
#include "rigid/broad_phase.hpp"
#include "rigid/contact_cache.hpp"
#include "rigid/contact_solver.hpp"
#include "rigid/islands.hpp"
#include "rigid/joint_solver.hpp"
#include "rigid/piece_contacts.hpp"
#include "rigid/solver_body.hpp"

namespace pba::rigid {

using RigidSettings = ContactSettings;

class RigidSystem {
public:
    /// For the World's ClonePtr: a world copies its rigid system whole, contacts and sleep included.
    std::unique_ptr<RigidSystem> clone() const { return std::make_unique<RigidSystem>(*this); }
    /// The world's body `worldIndex` (a RigidBody) joins the system.
    void add(std::size_t worldIndex);
    /// The world's particle `worldIndex` joins the system as a point body.
    void addPoint(std::size_t worldIndex);
    bool isPoint(std::size_t k) const { return m_isPoint[k] != 0; }
    /// What a point body is for one step: the particle's states before and after its own step.
    struct PointBody {
        RigidState start, end; ///< orientation the identity, no angular momentum
        double mass = 1.0, radius = 0.0, friction = 0.0, restitution = 1.0;
        Integrator integrator = Integrator::SemiImplicitEuler;
        bool fixed = false;
        /// Met by the rigid bodies inside its own method's substeps (XPBD's,
        /// xpbd_rigid_contacts.hpp): here it is only joined.
        bool metInSubsteps = false;
    };
    std::size_t size() const { return m_world.size(); }
    std::size_t worldIndex(std::size_t k) const { return m_world[k]; }
    RigidSettings& settings() { return m_settings; }
    const RigidSettings& settings() const { return m_settings; }

    // ---- the step's phases ----
    /// Reads every rigid body's start state and what it is made of from the world's bodies
    /// (null for a point body, which setPoint gives).
    void begin(std::span<const RigidBody* const> bodies);
    /// Point body k this step (after begin).
    void setPoint(std::size_t k, const PointBody& point);
    /// The awake bodies (system indices) that the World integrates freely this step.
    const std::vector<std::uint32_t>& awake() const { return m_awake; }
    const RigidState& start(std::size_t k) const { return m_start[k]; }
    /// What body k's free step ended at.
    void setFreeEnd(std::size_t k, const RigidState& end) { m_end[k] = end; }
    /// Finds this step's contacts (broad phase, narrow phase, room, warm start) and wakes the
    /// sleeping islands an awake body touches: those bodies are listed by woken(), for the World
    /// to integrate before solve().
    void findContacts(std::span<const Plane> planes, double dt);
    const std::vector<std::uint32_t>& woken() const { return m_woken; }
    /// Islands, the contact solver and sleep; `gravity` sets the speed below which a point does
    /// not bounce. Then end(k) is body k's state at the end of the step.
    void solve(const dvec3& gravity, double dt);
    const RigidState& end(std::size_t k) const { return m_end[k]; }

    /// The segments of the ropes' and cloths' nets between their point bodies, and the cloths'
    /// triangles of three: held out of the bodies where a body lies between their balls.
    void setPieces(std::vector<Segment> segments, std::vector<std::array<std::uint32_t, 3>> triangles)
    {
        m_segments = std::move(segments);
        m_triangles = std::move(triangles);
    }

    // ---- joints ----
    /// A joint between two of the system's bodies, or (b == kWorldBody) between a and the world.
    void addJoint(const Joint& joint);
    const std::vector<Joint>& joints() const { return m_joints; }
    /// The index the solver gives the world (a static body): after the bodies, before the room.
    BodyIndex worldBody() const { return BodyIndex(m_world.size()); }

    // ---- read-outs ----
    bool isAsleep(std::size_t k) const { return m_motion[k] == Motion::Asleep; }
    /// Every contact of the last step (body pairs by system index; a room surface is
    /// size() + 1 + its surface id).
    const std::vector<Contact>& contacts() const { return m_cache.contacts(); }
    /// The islands of the last step's solve (for statistics and pictures).
    const Islands& islands() const { return m_islands; }
    /// Wakes every body (a program changed something the contacts cannot see: a force, a pose).
    void wakeAll();
    /// Wakes body k and keeps it awake this step: something outside the system pushed it (a
    /// particle stepped by XPBD, as a particle's contact here keeps its island awake).
    void keepAwake(std::size_t k);
    /// Forgets every contact (the room changed, or a body was moved by hand).
    void clearContacts() { m_cache.clear(); }

private:
    struct Material {
        std::shared_ptr<const contact::CollisionShape> shape;
        double friction = 0.0, restitution = 0.0;
        double inverseMass = 0.0;
        dmat3 inverseInertiaBody{0.0};
        double driftWeight = 1.0;
        bool metInSubsteps = false; ///< a point body's (PointBody)
        /// A point body's spring joints are springs of its own method's solve (XPBD's substeps,
        /// backward Euler's joint points: world_particle_systems.cpp): not applied here.
        bool springJointsInItsSolve = false;
    };
    bool anythingAwake() const { return !m_awake.empty() || !m_points.empty(); }
    /// Whether a contact between a and b is left out: two bodies a joint joins (unless it says
    /// they collide).
    bool joinedApart(BodyIndex a, BodyIndex b) const;
    void boundingBoxes(double dt);
    /// A body that its partners may strike harder than the contact margin covers reaches as far
    /// as they may push it: wider partners and contacts (m_reach).
    void widenForPushes();
    void collidePairs();
    void collideRoom(std::span<const Plane> planes);
    void carrySleepingContacts();
    void wakeTouched();
    void wakeIsland(std::uint32_t body);
    void prepareBodies(double dt, std::size_t surfaces);
    /// An island's three passes (contact_solver.hpp), with its joints' sweeps among them.
    void solveIsland(std::size_t island, const SolverSettings& settings);
    /// The island's joints that its solve holds: all but the spring joints of a moving point met
    /// in its own substeps, which hold them there.
    std::span<const std::uint32_t> solvedLinks(std::size_t island) const;
    /// Whether a joint's spring is applied by its point's own solve rather than this one's.
    bool appliedElsewhere(const Joint& j) const;
    static void solveMechanismVelocities(ContactSolver& solver, JointSolver& joints, const SolverSettings& settings);
    void moveEndPoses(std::size_t island, const ContactSolver& solver, double dt);
    /// `methodWork`: what the bodies' own methods add beyond the free step (explicitSpringWork).
    void capEnergy(std::size_t island, double methodWork);
    /// Whether no contact or joint ties the island to a static body or the world.
    bool heldByNothing(std::size_t island) const;
    /// What the island's spring joints store at the start, after the free step and now.
    struct Energies {
        double start = 0.0, free = 0.0, end = 0.0;
    };
    Energies springEnergy(std::size_t island) const;
    /// Each of `bodies` out of the room, if it is beyond a surface; those it moved further than
    /// the slop into `moved`.
    void pushOutOfRoom(std::span<const std::uint32_t> bodies, std::vector<std::uint32_t>* moved = nullptr);
    /// The position pass's sweeps over an island without joints, found again where they moved
    /// a body beyond its contacts' reach.
    void sweepPositions(std::size_t island, ContactSolver& solver, std::vector<Contact>& atEnd, int sweeps);
    /// Sweeps over the end poses' points after the last push-out (ContactSolver::settleOn).
    static constexpr int kSettleSweeps = 2;
    void contactsAtEnd(std::size_t island, std::vector<Contact>& out) const;
    /// Appends the end poses' contacts of `bodies` with the room and of the cache's `contacts`.
    void contactsAtEnd(std::span<const std::uint32_t> bodies, std::span<const std::uint32_t> contacts,
                       std::vector<Contact>& out) const;
    /// How far apart the end poses' contacts of a and b reach (b may be a surface of the room).
    double positionMargin(BodyIndex a, BodyIndex b) const;
    /// The room's contacts of `bodies` at their end poses, within `margin` (by default the
    /// position pass's, positionMargin); none for a point body.
    void roomAtEnd(std::span<const std::uint32_t> bodies, std::vector<Contact>& out,
                   std::optional<double> margin = std::nullopt) const;
    void pairsAtEnd(std::span<const std::uint32_t> contacts, std::vector<Contact>& out) const;
    /// Every segment and triangle near a body, held out of it (holdPieces) at the end poses.
    void holdNets(const SolverSettings& settings);
    /// Segment s's contacts with the bodies near it, into `out`, and its balls into `balls` if any.
    void segmentContacts(const Segment& s, std::vector<PieceContact>& out, std::vector<std::uint32_t>& balls) const;
    /// The same for a triangle of three point bodies.
    void triangleContacts(const std::array<std::uint32_t, 3>& t, std::vector<PieceContact>& out,
                          std::vector<std::uint32_t>& balls) const;
    /// A piece's contact with `body`, held at `point` (world) by the point of these weights on its
    /// ends, its separation there and what its balls' line gives; its material by the weights.
    PieceContact pieceContact(const std::array<std::uint32_t, 3>& ends, const std::array<double, 3>& weights,
                              std::uint32_t body, const dvec3& normal, const dvec3& point, double separation,
                              double line) const;
    void finishBodies();
    void updateSleep(double dt);

    RigidSettings m_settings;
    std::vector<std::size_t> m_world; ///< each body's index in the world
    std::vector<Material> m_material;
    std::vector<Motion> m_motion;
    std::vector<std::uint8_t> m_isPoint;
    std::vector<std::uint32_t> m_points; ///< the moving point bodies of this step
    std::vector<Segment> m_segments;
    std::vector<std::array<std::uint32_t, 3>> m_triangles;
    std::vector<std::uint64_t> m_joinedApart; ///< sorted keys of the pairs joined and not colliding
    std::vector<double> m_stillFor; ///< seconds below the sleep speed
    std::vector<RigidState> m_start, m_end;
    std::vector<double> m_reach; ///< how far any point of the body moves in the step, or is pushed
    std::vector<double> m_spinReach; ///< the share of m_reach that the body's spin gives
    /// How far a partner may push a body in the step, and which way.
    struct Push {
        double length = 0.0;
        dvec3 low{0.0}, high{0.0}; ///< along -x, -y, -z and along +x, +y, +z
    };
    std::vector<Push> m_push;
    std::vector<Box> m_boxes;
    std::vector<Plane> m_planes;
    dvec3 m_gravity{0.0};
    /// Each awake body's energy in gravity at the start and at the end of its free step.
    std::vector<double> m_energyStart, m_energyFree;
    std::vector<std::uint32_t> m_awake, m_woken;
    /// Each sleeping island's bodies, and each sleeping body's island there.
    std::vector<std::vector<std::uint32_t>> m_sleepingIslands;
    std::vector<std::uint32_t> m_sleepingIsland;

    BroadPhase m_broadPhase;
    std::vector<BodyPair> m_pairs;
    ContactCache m_cache;
    std::vector<std::vector<Contact>> m_roomChunks;
    std::size_t m_surfaces = 0;
    Islands m_islands;
    std::vector<Joint> m_joints;
    std::vector<Link> m_links;
    std::vector<SolverBody> m_solverBodies;
    std::vector<std::uint32_t> m_islandOrder; ///< the islands, largest first
};

} // namespace pba::rigid
