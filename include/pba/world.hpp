#pragma once
// The World owns bodies, forces and the surfaces that bound them, and advances them by
// a fixed dt. It is made of parts, each the data of one concern (as Jolt's PhysicsSystem is
// made of a body manager, a broad phase, a contact manager...); they are World's private
// members, declared at the end of this file (their code in src/core/, a folder each):
//   Bodies           (bodies/) every body, and what the step keeps of each (previous state and
//                    rotation, mass, restitution, coupling key, state and pose at the current
//                    stage, bounces, the first one not finite or inside a surface)
//   Forces           (forces/) the forces, the pairs of bodies they couple, and their accumulators
//   ParticleSystems  (particle_systems/, balls/) the coupling of the moving particles into
//                    systems, one per integrator, their scratch, implicit-euler's and xpbd's
//                    spring solvers, and the contacts of the particles with a radius
//   RigidBodies      (rigid/, contact/) the rigid system (broad phase, narrow phase, contact
//                    cache, islands with their sleep, contact solver and joints) and the
//                    buffers of the bodies' free step
//   Swarms           (swarms/) the swarms (float arrays, all cores) and their copies for a rollback
//   Surfaces         (surfaces/) the ground or the room, the floor hole, their planes, the
//                    collision response
//   StepClock        the time and the step count (the clocks that drive it: clock/)
// step() runs in named phases (the way Box2D's solver stages and Jolt's step jobs are named),
// each a function over one part or a named few:
//   1. Bodies::storePreviousStates (and Swarms::keepForRollback): the states before the step,
//      for the renderer's interpolation and the rollback, reading each body's object once for
//      all the step needs of it (state, mass, restitution, key)
//   2. couple: bodies joined (transitively) by forces between bodies, such as a two-body
//      spring, form a coupled group that shares one integrator (kept from step to step, made
//      anew when a body's fixed flag or integrator changes)
//   3. integrateIndependent: each other particle with its own integrator, with collisions along
//      its own path (the exact time of impact): forces are summed at every trial state
//   4. integrateParticleSystems: one system per integrator. integrateCoupled: every stage of
//      an explicit method evaluates every force for every body of the system at that stage's
//      state (RK4 of a coupled system is RK4 of the whole system); implicit-euler's and xpbd's
//      systems (every moving particle that takes them, joined by springs or not) take their
//      own steps: integrateBackwardEuler solves for the velocities with the springs' Jacobian,
//      integrateXpbd projects the springs as constraints in substeps. Each ends in
//      collideAndStore: a body found behind a surface gets the reflect or clamp rule of its own
//      (exact acts as reflect for them), in the pass that writes its new state
//   5. stepRigidBodies: integrateRigidFreely steps each awake rigid body under every force, one
//      system per integrator, translation and rotation together; then the rigid system finds
//      their contacts with each other and with the room (findContacts), the bodies it woke take
//      their free step too, it solves the contacts and joints island by island and puts still
//      islands to sleep (solve), and storeRigidBodies writes each end state into its body
//   6. stepSwarms: the swarms with the same integrator, force and collision templates
//   7. checkFinite and checkInsideSurfaces: every state (bodies and swarms) was checked as it
//      was written, and each rigid body's centre against the surfaces; here the first one that
//      is not finite, or inside, rolls the step back and throws
//   8. StepClock::advance
// It knows no window, no file format and no clock: frame time never reaches it.
#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "pba/body.hpp"
#include "pba/clone_ptr.hpp"
#include "pba/collision.hpp"
#include "pba/contact_settings.hpp"
#include "pba/force.hpp"
#include "pba/joint.hpp"
#include "pba/particle.hpp"
#include "pba/rigid_body.hpp"
#include "pba/state.hpp"
#include "pba/swarm.hpp"
#include "pba/vec3_array.hpp"

namespace pba {

namespace rigid {
class RigidSystem;
}
namespace detail {
class SpringSystem;
struct SpringSolver;
struct SpringSolvers;
struct BallContacts;
class SpringNeighbours;
class GrainContacts;
class XpbdRigidContacts;
}

/// An axis-aligned box: the room.
struct Aabb {
    dvec3 min{0.0};
    dvec3 max{0.0};
};

/// A round hole in the floor with a grille `depth` below it (the blow dryer's).
struct FloorHole {
    dvec3 centre{0.0}; ///< on the floor
    double radius = 0.0;
    double depth = 0.05;
};

/// A run that blew up: a state that cannot be, found by World::step (a position, a velocity
/// or an orientation that stopped being finite, a rigid body's centre of mass inside a surface)
/// or by a BlowUpWatch (an energy that is not finite, or that grew with nothing to feed it).
/// `body` names the body ("SWARM[i]" for particle i of a swarm), `reason` says what happened to
/// it; what() is "REASON at step N (t = T s): try a smaller dt or another integrator".
class BlowUpError : public std::runtime_error {
public:
    BlowUpError(std::string body, std::uint64_t step, double time, std::string reason);
    const std::string& body() const { return m_body; }
    std::uint64_t step() const { return m_step; }
    double time() const { return m_time; }
    const std::string& reason() const { return m_reason; }

private:
    std::string m_body;
    std::uint64_t m_step;
    double m_time;
    std::string m_reason;
};

/// The blow-up of a state that stopped being finite: the reason is "the QUANTITY of body 'NAME'
/// is not finite".
class NonFiniteStateError : public BlowUpError {
public:
    NonFiniteStateError(std::string body, std::uint64_t step, double time, std::string quantity);
    /// For particle `index` of swarm `swarm`.
    static NonFiniteStateError inSwarm(const std::string& swarm, std::size_t index, std::uint64_t step, double time,
                                       std::string quantity);
    /// "position", "velocity", "angular velocity", "orientation" or "energy".
    const std::string& quantity() const { return m_quantity; }

private:
    std::string m_quantity;
};

class World {
public:
    World();
    World(const World&);
    World& operator=(const World&);
    World(World&&) noexcept;
    World& operator=(World&&) noexcept;
    ~World();

    // ---- bodies ----
    Body& addBody(std::unique_ptr<Body> body);
    Particle& addParticle(const Particle& particle);
    std::size_t bodyCount() const { return m_bodies.objects.size(); }
    Body& body(std::size_t i) { return *m_bodies.objects[i]; }
    const Body& body(std::size_t i) const { return *m_bodies.objects[i]; }
    std::optional<std::size_t> findBody(std::string_view name) const;

    // ---- joints between rigid bodies (or a rigid body and the world) ----
    /// Joins the bodies as `joint` says, its anchors and axis read in the world now. Throws
    /// std::invalid_argument naming what is wrong (a body that is not rigid, the same body
    /// twice, a zero axis, limits that do not hold the start's angle, a bad spring).
    std::size_t addJoint(const JointDesc& joint);
    std::size_t jointCount() const;
    /// Where joint i is now.
    JointFrame jointFrame(std::size_t i) const;

    // ---- swarms: many identical particles as float arrays, stepped with the same rules ----
    /// Throws std::invalid_argument if a force of the world cannot act on a swarm. The reference
    /// stays valid as more swarms are added (each swarm is an object of its own, as a body is).
    Swarm& addSwarm(const SwarmDesc& desc);
    std::size_t swarmCount() const { return m_swarms.objects.size(); }
    Swarm& swarm(std::size_t i) { return *m_swarms.objects[i]; }
    const Swarm& swarm(std::size_t i) const { return *m_swarms.objects[i]; }
    /// Threads for stepping swarms and coupled bodies (a cloth): 0 (the default) uses all cores;
    /// results do not depend on it. A world of fewer bodies than 2,048 steps its particles on one,
    /// where each of their loops is one block.
    void setThreads(int threads) { m_threads = threads; }
    /// The substeps of a step of the bodies that take `xpbd` (default kDefaultXpbdSubsteps).
    /// Throws std::invalid_argument unless it is from 1 to kMaxXpbdSubsteps.
    void setXpbdSubsteps(int substeps);
    int xpbdSubsteps() const { return m_particleSystems.xpbdSubsteps; }
    static constexpr int kDefaultXpbdSubsteps = 10;
    static constexpr int kMaxXpbdSubsteps = 10000;
    /// The conjugate-gradient iterations of implicit-euler's last step (0 without its system).
    int lastImplicitIterations() const;
    /// Keep a copy of every swarm before each step, so that a failed step rolls the swarms back
    /// with the bodies (the viewer pauses on the last finite state). Off by default: the copy
    /// doubles a swarm's memory and its traffic each step, and a program that stops at the
    /// failure has no use for it; without it the swarms keep the failed step's state.
    void setSwarmRollback(bool keep) { m_swarms.rollback = keep; }
    /// The forces that act on swarms, in float: gravity, drag and blow dryers.
    SwarmFields swarmFields() const;

    // ---- forces ----
    /// Throws std::invalid_argument if the world has swarms and the force cannot act on them
    /// (Force::addToSwarmFields).
    Force& addForce(std::unique_ptr<Force> force);
    std::size_t forceCount() const { return m_forces.objects.size(); }
    Force& force(std::size_t i) { return *m_forces.objects[i]; }
    const Force& force(std::size_t i) const { return *m_forces.objects[i]; }
    /// The gravitational acceleration of the world's Gravity forces (zero without any).
    dvec3 gravity() const;

    // ---- the surfaces ----
    void setGround(double height);
    void setRoom(const Aabb& room);
    void clearSurfaces();
    /// Cuts a hole in the floor (of the room or the ground); one hole at most, as the planes
    /// carry one each. Throws std::invalid_argument without a floor or for a bad radius/depth.
    void setFloorHole(const FloorHole& hole);
    const std::optional<FloorHole>& floorHole() const { return m_surfaces.hole; }
    const std::optional<double>& ground() const { return m_surfaces.ground; }
    const std::optional<Aabb>& room() const { return m_surfaces.room; }
    std::span<const Plane> planes() const { return m_surfaces.planes; }
    CollisionResponse collisionResponse() const { return m_surfaces.response; }
    /// The rule coupled bodies get: a coupled body has no path of its own to find a time of
    /// impact on (its group moves as one), so `exact` acts as `reflect` for it.
    CollisionResponse coupledCollisionResponse() const
    {
        return m_surfaces.response == CollisionResponse::Exact ? CollisionResponse::Reflect : m_surfaces.response;
    }
    /// Whether some bodies get another rule than collisionResponse(): coupled ones under `exact`.
    bool coupledBodiesReflect() const
    {
        return coupledCollisionResponse() != m_surfaces.response && hasCoupledBodies();
    }
    void setCollisionResponse(CollisionResponse response) { m_surfaces.response = response; }
    /// Whether the response has anything to act on: a particle or a swarm (rigid bodies meet the
    /// room with contact impulses whatever it is).
    bool hasPoints() const;

    // ---- stepping ----
    /// Advances every moving body and swarm by exactly dt. Throws std::invalid_argument (before
    /// moving anything) unless dt is finite and positive, if two moving bodies coupled by a
    /// force use different integrators, or if a rigid body takes implicit-euler or xpbd (methods
    /// for particles joined by springs). Throws BlowUpError, with the bodies (and with
    /// setSwarmRollback the swarms) back at their state before the step, if it made a state that
    /// cannot be: NonFiniteStateError for a position, velocity, orientation or angular momentum
    /// that is not finite (or an orientation that no longer has a length to normalise), and
    /// BlowUpError for a rigid body whose centre of mass ends on or beyond a surface (outside a
    /// floor hole's reach): at least half of it inside the floor or a wall, which its contacts
    /// never allow (they leave a point at most a step of gravity's sinking, g dt^2, beyond).
    void step(double dt);
    double time() const { return m_clock.time; }
    /// The time of the previous states (before the last step).
    double previousTime() const { return m_clock.previousTime; }
    std::uint64_t stepCount() const { return m_clock.steps; }
    /// The state before the last step (equal to the current one before any step).
    const State& previousState(std::size_t i) const { return m_bodies.previous[i]; }
    /// Blend of previous and current state for rendering, alpha in [0, 1).
    State interpolatedState(std::size_t i, double alpha) const;
    /// Body i's orientation blended (slerp) between the previous and the current step, as
    /// interpolatedState blends its position; the identity for a body that does not turn.
    dquat interpolatedOrientation(std::size_t i, double alpha) const;
    /// Whether body i is a RigidBody (it turns, and meets the room with contact impulses).
    bool isRigid(std::size_t i) const { return m_bodies.isRigid[i] != 0; }
    bool hasRigidBodies() const;
    /// Bounces of body i since the start.
    std::uint64_t bounceCount(std::size_t i) const { return m_bodies.bounces[i]; }
    /// Whether rigid body i sleeps: it and every body it touches have been still for a while,
    /// and none of them moves until an awake body touches one (see ContactSettings).
    bool isAsleep(std::size_t i) const;
    /// Wakes every sleeping body (after a program changed a force or moved a body by hand).
    void wakeAll();
    /// A contact point of the last step, for drawing: where it was, its normal (from the first
    /// body towards the second, or into the room's surface) and the normal impulse it took.
    struct ContactPointView {
        dvec3 point{0.0};
        dvec3 normal{0.0};
        double impulse = 0.0;
        double separation = 0.0;         ///< where the step found it: below zero, an overlap
        std::size_t bodyA = 0;           ///< world index
        std::optional<std::size_t> bodyB; ///< world index; none for the room
    };
    /// Every touching contact point of the last step (separation below a millimetre or pushing).
    std::vector<ContactPointView> contactPoints() const;
    /// The same into `out`, whose storage a caller that looks after every step keeps.
    void contactPoints(std::vector<ContactPointView>& out) const;
    /// How contacts and joints are solved, and when bodies sleep.
    ContactSettings& contactSettings();
    const ContactSettings& contactSettings() const;
    /// The rigid bodies' contact pipeline: its settings, contacts and joints.
    rigid::RigidSystem& rigidSystem() { return *m_rigid.system; }
    const rigid::RigidSystem& rigidSystem() const { return *m_rigid.system; }

    // ---- physics read-outs ----
    /// Net force over mass on body i at the trial state (x, v), every other body at its
    /// current state; zero for a fixed body.
    dvec3 acceleration(std::size_t i, const dvec3& x, const dvec3& v) const;
    /// Translational kinetic energy, and a rigid body's rotational 1/2 omega . L.
    double kineticEnergy(std::size_t i) const;
    /// Body i's potential energy: its share of each force's (a force between bodies splits its
    /// energy among them, a two-body spring half to each end) and of each spring joint's, so the
    /// shares add up to totalPotentialEnergy.
    double potentialEnergy(std::size_t i) const;
    double energy(std::size_t i) const { return kineticEnergy(i) + potentialEnergy(i); }
    /// Every body's energy(i) at once. One body's potential energy reads every body's state, so
    /// asking for each of a cloth's 16,384 bodies in turn would cost bodies squared; this
    /// gathers the states once.
    std::vector<double> energies() const;
    /// Every force's potential energy, each interaction counted once, and what the spring
    /// joints store.
    double totalPotentialEnergy() const;
    /// Kinetic plus potential energy of all bodies (swarms not included).
    double totalEnergy() const;
    /// Whether any force may add energy (Force::addsEnergy: the blow dryer, a program's own force).
    bool hasEnergySources() const;
    /// What the forces that may add energy (Force::addsEnergy: the blow dryer, a program's own
    /// force) exert on each body now, a wrench per body: zero on a fixed one, and on every body
    /// when no force may add energy (swarms not included, as in totalEnergy). Given `states` (one
    /// per body), at those positions and velocities instead, each body turned as it is now.
    std::vector<Wrench> sourceWrenches(std::span<const State> states = {}) const;
    /// The work the energy sources did over the last step on each particle that moves alone or in
    /// a system of an explicit method (forward or semi-implicit Euler, velocity Verlet, RK4),
    /// exact: each stretch of its free flight booked as its integrator took it, every stage
    /// weighing the sources' force as it weighs the whole force (stageWeights), so that this is
    /// their share of the kinetic energy the flight gave. NaN for every other body (rigid, fixed,
    /// of an implicit-euler or xpbd system); empty in a world without an energy source.
    std::span<const double> lastStepSourceWork() const { return m_bodies.sourceWork; }
    /// Whether body i is integrated in a coupled group: it moves, and a force couples it to a
    /// body, or it takes implicit-euler or xpbd (whose step is a system's, joined by springs or not).
    bool isCoupled(std::size_t i) const;
    /// Whether bodies a and b, particles with a radius, collide as balls after their steps: not
    /// neighbours along one rope's or cloth's springs, which hold them instead (as of the last
    /// step: false for a body added since).
    bool ballsCollide(std::size_t a, std::size_t b) const;
    /// Whether any moving body is coupled: then `exact` acts as `reflect` on those bodies.
    bool hasCoupledBodies() const;
    /// The moving bodies joined to body i (transitively, through moving bodies) by forces
    /// between bodies, i included, in index order: the group that shares one integrator.
    std::vector<std::size_t> coupledGroup(std::size_t i) const;

private:
    // ---- the parts: each phase of step() works on one of them (or a named few) ----

    /// The bodies, and what the step keeps of each, by world index.
    struct Bodies {
        std::vector<ClonePtr<Body>> objects;
        std::vector<State> previous;          ///< each body's state before the last step
        std::vector<Rotation> previousRotation; ///< rigid bodies' (the identity for the others)
        std::vector<std::uint8_t> isRigid;
        /// Each body's index in the rigid system (kNotRigid for a particle).
        std::vector<std::uint32_t> rigidIndex;
        /// What storePreviousStates read of each body besides its state: mass, restitution, and
        /// the key of its coupling (fixed flag and integrator).
        std::vector<double> masses, cors;
        /// Each particle's radius and Coulomb friction, read with its mass (0 for a rigid body:
        /// its shape says where it touches).
        std::vector<double> radii, frictions;
        std::vector<std::uint8_t> isParticle;
        std::vector<std::uint8_t> keys;
        /// Each body's state and pose at the current stage of an integrator (BodyStates): the
        /// start of the step for every body but those of the system being integrated.
        std::vector<State> trial;
        std::vector<Pose> poses;
        /// Each rigid body's acceleration at the start of its last free step.
        std::vector<dvec3> rigidAcc;
        std::vector<std::uint64_t> bounces;
        /// The energy sources' work over the last step (lastStepSourceWork).
        std::vector<double> sourceWork;
        /// The lowest index of a body whose state the step made not finite; bodyCount() if none.
        std::size_t firstNonFinite = 0;
        /// The lowest index of a rigid body the step left with its centre inside a surface;
        /// bodyCount() if none.
        std::size_t firstInside = 0;

        /// Phase 1: each body's state before the step, for the renderer's interpolation and the
        /// rollback, with all else the step reads of its object (mass, restitution, key).
        void storePreviousStates();
        /// Notes body i as not finite if its new state is not.
        void noteIfNotFinite(std::size_t i, const State& state);
        /// Every body back at its state before the step.
        void rollBack();
    };
    /// The forces, the pairs of bodies they couple, and the accumulators they add to.
    struct Forces {
        std::vector<ClonePtr<Force>> objects;
        /// Every force's coupled pairs (Force::appendCouplings), gathered as the forces are added.
        std::vector<std::pair<std::size_t, std::size_t>> couplings;
        std::vector<std::size_t> couplingForce; ///< the force of each pair, for the messages
        /// Every body's force and torque at the current stage (Accumulators), and the forces'
        /// working memory (Accumulators::scratch).
        std::vector<dvec3> sums, torques, scratch;
        std::vector<dvec3> sourceSums; ///< the energy sources' share of sums, when booked
    };
    /// The bodies integrated together: the moving bodies some force couples, by integrator (one
    /// system each), and the others. Kept from step to step (a cloth's 97,000
    /// springs are not walked every step) with what it was made from: each body's fixed flag and
    /// integrator, which a program may change between steps.
    struct Coupling {
        /// By kParticleIntegrators: each method's system.
        std::array<std::vector<std::size_t>, kParticleIntegrators.size()> systems;
        std::vector<std::size_t> independent; ///< every other body, fixed ones too, in order
        /// Per system, one flag per body of the world: its members (the forces' wanted list).
        std::array<std::vector<std::uint8_t>, kParticleIntegrators.size()> wanted;
        std::vector<std::uint8_t> madeFrom;
    };
    /// A coupled system's buffers, reused so that a step allocates (almost) nothing.
    struct CoupledScratch {
        Vec3Array x, v, acc; ///< the system's state, and its acceleration at the start
        std::vector<double> mass; ///< the spring systems': each member's
        /// Each member's impulse of the energy sources over the step, its stages weighed as the
        /// method weighs them (lastStepSourceWork).
        std::vector<dvec3> sourceImpulse;
    };
    /// The particles integrated as systems: the coupling, and what each method keeps.
    struct ParticleSystems {
        Coupling coupling;
        CoupledScratch scratch;
        ClonePtr<detail::SpringSolvers> springSolvers; ///< implicit-euler's and xpbd's
        /// The particles with a radius against each other: their grid, pairs and balls.
        ClonePtr<detail::BallContacts> ballContacts;
        /// Which of them one rope's or cloth's springs hold too near to collide.
        ClonePtr<detail::SpringNeighbours> neighbours;
        /// A colliding swarm's grains against each other: their cell order, slabs and pairs.
        ClonePtr<detail::GrainContacts> grainContacts;
        int xpbdSubsteps = kDefaultXpbdSubsteps;
    };
    /// The free step's buffers of the rigid bodies, reused from step to step.
    struct RigidScratch {
        std::vector<RigidState> states;
        std::vector<RigidInertia> inertia;
        std::vector<dvec3> startAcc;
        std::array<std::vector<std::size_t>, kEveryIntegrator.size()> members; ///< awake, by integrator
        std::vector<std::uint8_t> wanted;
        std::vector<std::size_t> place; ///< by world index: its place among the members (pushAtFreeEnd)
        RigidStepBuffers buffers;
    };
    /// The rigid bodies: their contact pipeline (src/core/rigid/: broad phase, narrow phase,
    /// contact cache, islands, solver and joints) and the buffers of their free step.
    struct RigidBodies {
        ClonePtr<rigid::RigidSystem> system;
        RigidScratch scratch;
        std::size_t bodiesSeen = 0; ///< the bodies looked at for particles with a radius
        /// What the system's segments and triangles were made from: the neighbours' generation, and the bodies.
        std::uint64_t piecesGeneration = 0;
        std::size_t piecesBodies = 0;
        /// Impulses on bodies at the end of their free step this step (what an implicit-Euler
        /// sheet's held members did to them): world index, impulse, angular impulse.
        struct EndPush {
            std::size_t body = 0;
            dvec3 impulse{0.0}, angular{0.0};
        };
        std::vector<EndPush> endPushes;
    };
    /// The swarms, and their copies for a rollback.
    struct Swarms {
        std::vector<ClonePtr<Swarm>> objects; ///< each its own object: addSwarm's references stay valid
        bool rollback = false;
        std::vector<std::vector<float>> before; ///< with rollback: each swarm before the step

        /// With rollback: a copy of each swarm before the step.
        void keepForRollback();
        /// With rollback: each swarm back at its copy.
        void rollBack();
    };
    /// What bounds the bodies and swarms, and how they bounce off it.
    struct Surfaces {
        std::optional<double> ground;
        std::optional<Aabb> room;
        std::optional<FloorHole> hole;
        std::vector<Plane> planes; ///< made of the three above
        CollisionResponse response = CollisionResponse::Exact;

        /// The planes of the ground or the room, with the hole cut in the floor and its grille.
        void rebuildPlanes();
    };
    /// The time of the world, which each step advances.
    struct StepClock {
        double time = 0.0;
        double previousTime = 0.0;
        std::uint64_t steps = 0;
        double lastDt = 0.0;       ///< dt of the previous step
        double baseTime = 0.0;     ///< time when dt last changed
        std::uint64_t baseSteps = 0;

        /// Phase 8: the time after a step of dt.
        void advance(double dt);
    };
    static constexpr std::uint32_t kNotRigid = 0xffffffffu;

    // ---- the phases of step(), in order; the parts each works on in brackets ----
    /// Phase 2 (ParticleSystems, from Bodies and Forces): the coupling, made anew if a body's
    /// key changed. Throws for a coupled pair that cannot share an integrator.
    const Coupling& couple();
    Coupling makeCoupling() const;
    /// Phase 2b (Bodies, from Forces): the book of the energy sources' work over this step
    /// (lastStepSourceWork) opened, every body NaN until its integration books it, in a world
    /// with an energy source; closed (empty) in one without.
    void openSourceBook();
    /// Phase 3 (Bodies, Forces, Surfaces): each body alone with its integrator, colliding
    /// along its own path.
    void integrateIndependent(const std::vector<std::size_t>& bodies, double dt);
    /// The force on body i at state (x, v), and the energy sources' (Force::addsEnergy) share
    /// of it, summed in one pass over the forces.
    struct ForceOnBody {
        dvec3 total{0.0};
        dvec3 sources{0.0};
    };
    ForceOnBody forceOn(std::size_t i, const dvec3& x, const dvec3& v) const;
    /// Phase 4 (ParticleSystems, Bodies, Forces, Surfaces): each particle system with its
    /// method, then collideAndStore.
    void integrateParticleSystems(const Coupling& coupling, double dt);
    void integrateCoupled(Integrator integrator, const std::vector<std::size_t>& members,
                          std::span<const std::uint8_t> wanted, double dt);
    void integrateBackwardEuler(const std::vector<std::size_t>& members, std::span<const std::uint8_t> wanted,
                                double dt);
    void integrateXpbd(const std::vector<std::size_t>& members, std::span<const std::uint8_t> wanted, double dt);
    /// For xpbd: the rigid bodies its substeps meet, started for the step (null: none near), and
    /// what they took from the members in them, given to them.
    detail::XpbdRigidContacts* startXpbdRigidContacts(const std::vector<std::size_t>& members,
                                                      detail::SpringSolver& solver, double dt);
    void giveXpbdReactions(const detail::XpbdRigidContacts& bodies);
    /// For backward Euler: each member resting on a ball below it (of the last step's contacts)
    /// held on it as on a surface, its normal into heldOn (those held on the room keep theirs).
    void holdOnBalls(const std::vector<std::size_t>& members, std::span<dvec3> heldOn, double dt) const;
    /// For backward Euler: each member resting on a rigid body (of the last step's contacts, at
    /// the poses now) held on it, its normal into solver.heldOn (those held on the room or a ball
    /// keep theirs); a moving body is one of the solve's bearers (backward_euler.hpp).
    void holdOnBodies(const std::vector<std::size_t>& members, detail::SpringSolver& solver, double dt) const;
    /// The moving rigid bodies (world indices, sorted) resting on the room or a fixed body now.
    std::vector<std::size_t> supportedBodies() const;
    /// The bearer of the solve for body `world` (added if new).
    std::uint32_t bearerFor(detail::SpringSolver& solver, std::size_t world, double dt) const;
    /// After the solve: friction on the members held on rigid bodies or the room, and what the
    /// held members did to their bearers, as impulses at the end of those bodies' free steps.
    void rubAndPushBearers(const std::vector<std::size_t>& members, detail::SpringSolver& solver, double dt);
    /// For backward Euler: each member's mass in the solve (solver.solveMass), with the mass and
    /// weight of a rigid body a ball joint joins it to (solver.carried), added to its start force.
    void carryJoinedBodies(const std::vector<std::size_t>& members, detail::SpringSolver& solver) const;
    /// After the solve: what the springs did to each carried mass, as an impulse on its body.
    void pushCarriedBodies(detail::SpringSolver& solver, double dt);
    /// A rope's or cloth's impulse and moment on rigid body `body` (a world index) before the
    /// body's own step, which then starts from the changed velocities, awake. (A bearer's pushes
    /// come at the end of its free step instead: rubAndPushBearers.)
    void pushBeforeItsStep(std::size_t body, const dvec3& impulse, const dvec3& moment);
    /// The system's start-of-step state into the particle systems' scratch (x and v).
    void startSystem(const std::vector<std::size_t>& members);
    /// The sources' forces on the system's members at the stage sumSystemForces just summed,
    /// times `weight`, added to their impulses (CoupledScratch::sourceImpulse).
    void bookSourceStage(const std::vector<std::size_t>& members, std::span<const std::uint8_t> wanted,
                         double weight);
    /// Every force on the system's members at the states (x, v) (at m_bodies.trial if x is
    /// empty), every other body at its start-of-step state: the members' sums in m_forces.sums.
    /// A spring of `constraints`, if given, is left out (xpbd's constraints).
    void sumSystemForces(const std::vector<std::size_t>& members, std::span<const std::uint8_t> wanted,
                         std::span<const dvec3> x, std::span<const dvec3> v, const detail::SpringSystem* constraints);
    /// The forces whose index `keep` takes, on the system's members at m_bodies.trial, summed
    /// into `sums` (the members' entries zeroed first).
    void sumForcesOnMembers(const std::vector<std::size_t>& members, std::span<const std::uint8_t> wanted,
                            std::vector<dvec3>& sums, const std::function<bool(std::size_t)>& keep);
    /// The spring solver of implicit-euler (or xpbd) made for the system, the system started
    /// with its masses, and the springs' fixed ends placed.
    detail::SpringSolver& startSpringSystem(const std::vector<std::size_t>& members, bool xpbd);
    /// The system's end states through the surfaces into its bodies, each checked finite.
    void collideAndStore(const std::vector<std::size_t>& members, double dt, Integrator integrator);
    /// Phase 4b (ParticleSystems, Bodies, Surfaces): the particles with a radius that touch each
    /// other after their step are separated and exchange impulses (src/core/balls/particle_contacts.hpp),
    /// and so are the balls and two nets' crossing edges between other ropes' and cloths' balls
    /// (src/core/balls/net_pieces.hpp);
    /// neighbours along one rope or cloth are left to their springs (src/core/particle_systems/spring_neighbours.hpp).
    void collideBalls(double dt);
    /// Phase 6, for a swarm that collides: its grains against each other and `room` (its planes
    /// moved a grain's radius inwards) by the particles' rule, in float and on all cores
    /// (`restingSpeed`: gravity's speed in one step).
    void collideGrains(Swarm& swarm, std::size_t slot, std::span<const PlaneT<float>> room, double restingSpeed,
                       double dt);
    /// Phase 5 (RigidBodies, Bodies, Forces, Surfaces): the awake bodies' free step
    /// (integrateRigidFreely), the rigid system's findContacts, the free step of the bodies it
    /// woke, its solve, then storeRigidBodies.
    void stepRigidBodies(double dt);
    void integrateRigidFreely(std::span<const std::uint32_t> bodies, double dt);
    /// The free step's end states of `members` (all of `integrator`) given this step's end pushes.
    void pushAtFreeEnd(Integrator integrator, const std::vector<std::size_t>& members, double dt);
    void stepRigid(Integrator integrator, const std::vector<std::size_t>& members, std::span<const std::uint8_t> wanted,
                   double dt);
    void storeRigidBodies();
    /// The particles that touch rigid bodies (those with a radius, in a world with rigid bodies)
    /// join the rigid system as point bodies; each step gives it their states and takes back
    /// what their contacts and joints made of them.
    void joinPointBodies();
    /// The nets' pieces (segments and triangles) between point bodies, given to the rigid system when they change.
    void givePieces();
    void givePointBodies();
    void storePointBodies();
    /// Phase 6 (Swarms, Forces, Surfaces).
    void stepSwarms(double dt);
    /// Phase 7 (Bodies, Swarms, Surfaces): the first state that cannot be rolls the step back
    /// (Bodies and Swarms) and throws.
    void checkFinite(double dt);
    void checkInsideSurfaces(double dt);
    void rollBack();

    /// Every body's state (and, in a world with rigid bodies, its pose) as the read-outs see it.
    /// The bodies now, for a force evaluation; without `withStates`, their poses only (the
    /// caller gives the states).
    BodyStates currentStates(std::vector<State>& storage, std::vector<Pose>& poses, bool withStates = true) const;
    /// Adds each spring joint's stored energy, 1/2 k (stretch)^2, to its bodies' entries of
    /// `perBody` (half to each; all to a body joined to the world), and returns their sum.
    double addSpringJointEnergies(std::span<double> perBody) const;

    Bodies m_bodies;
    Forces m_forces;
    ParticleSystems m_particleSystems;
    RigidBodies m_rigid;
    Swarms m_swarms;
    Surfaces m_surfaces;
    StepClock m_clock;
    int m_threads = 0; ///< the most any phase of the step uses
};

} // namespace pba
