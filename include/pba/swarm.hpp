#pragma once
// Swarms: many identical particles sharing one mesh, stored as structure-of-arrays floats
// (24 bytes a particle; with the exact response, one byte more remembering whether it is clear
// of every surface) and stepped by the same integrator, force-kernel and collision templates
// as a single Particle, instantiated for float and inlined into a loop the compiler vectorises. A Particle stays a readable object; a million of them live here.
#include <array>
#include <atomic>
#include <cstdint>
#include <algorithm>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "pba/blow_dryer.hpp"
#include "pba/clone_ptr.hpp"
#include "pba/collision.hpp"
#include "pba/forces.hpp"
#include "pba/integrator.hpp"
#include "pba/large_array.hpp"
#include "pba/math.hpp"

namespace pba {

/// How a swarm is made (the scene's "swarms" entries).
struct SwarmDesc {
    std::string name;
    std::size_t count = 0;
    dvec3 regionMin{0.0}; ///< initial positions are uniform in this box
    dvec3 regionMax{0.0};
    dvec3 velocity{0.0};  ///< initial velocity of every particle ...
    double velocityJitter = 0.0; ///< ... plus a uniform offset in [-jitter, jitter] per component, m/s
    double mass = 1.0;
    double restitution = 1.0;
    double radius = 0.0;   ///< every particle's, m; 0: points
    double friction = 0.0; ///< Coulomb mu between its particles when they collide
    bool collide = false;  ///< its particles collide with each other (they need a radius)
    Integrator integrator = Integrator::SemiImplicitEuler;
    std::uint64_t seed = 1;
};

/// The uniform fields that act on swarm particles, in float: gravity, linear drag and blow
/// dryers. Each force adds its own (Force::addToSwarmFields); one that cannot, such as a spring
/// tied to one named particle, is refused by a World with swarms.
struct SwarmFields {
    Vec3<float> gravity{0.0f};
    float drag = 0.0f;
    std::vector<BlowDryerFieldT<float>> dryers;
};

struct SwarmKernelFields; // pba/detail/swarm_kernel.hpp

/// Where a swarm's step spends its time, phase by phase, summed over its threads: filled while a
/// swarm has it (Swarm::setPhaseTimes), read by `pba bench --phases`. Each block of 512
/// particles reads the clock between its phases (a few tens of nanoseconds each), so a timed
/// step runs a little slower than an untimed one.
struct SwarmPhaseTimes {
    enum Phase { Integrate, SurfaceTest, Collide, Check, kCount };
    static constexpr std::array<const char*, kCount> kNames{"integrate", "surface test", "collide", "check"};
    std::array<std::atomic<std::uint64_t>, kCount> nanoseconds{};
};

class Swarm;

/// Told of each range of a swarm's particles as soon as its step is done with them, on the
/// thread that stepped them and while their states are still in that core's caches: a watch over
/// a million particles reads them there rather than from memory in a pass of its own. Ranges are
/// whole 512-particle blocks, disjoint, and come in any order, several at once (only positions
/// and velocities are final: a colliding swarm's grain contacts come after).
class SwarmRangeObserver {
public:
    virtual ~SwarmRangeObserver() = default;
    virtual void stepped(const Swarm& swarm, std::size_t begin, std::size_t end) = 0;
};

class Swarm {
public:
    /// Positions and velocities from a counter-based generator: particle i's values depend on
    /// (seed, i) only, so they do not depend on how the work is split.
    explicit Swarm(const SwarmDesc& desc);
    Swarm(const Swarm&);
    Swarm(Swarm&&) noexcept;
    Swarm& operator=(const Swarm&);
    Swarm& operator=(Swarm&&) noexcept;
    ~Swarm();
    /// A deep copy (what a World's copy makes of its swarms).
    std::unique_ptr<Swarm> clone() const;

    const SwarmDesc& desc() const { return m_desc; }
    const std::string& name() const { return m_desc.name; }
    std::size_t size() const { return m_count; }
    float mass() const { return m_mass; }
    float restitution() const { return m_restitution; }
    /// Every particle's radius (m) and Coulomb friction, as the desc says.
    float radius() const { return float(m_desc.radius); }
    float friction() const { return float(m_desc.friction); }
    Integrator integrator() const { return m_integrator; }
    void setIntegrator(Integrator integrator) { m_integrator = integrator; }
    void setRestitution(float restitution) { m_restitution = restitution; }

    Vec3<float> position(std::size_t i) const { return {array(0)[i], array(1)[i], array(2)[i]}; }
    Vec3<float> velocity(std::size_t i) const { return {array(3)[i], array(4)[i], array(5)[i]}; }
    void set(std::size_t i, const Vec3<float>& x, const Vec3<float>& v);
    std::span<const float> px() const { return {array(0), m_count}; }
    std::span<const float> py() const { return {array(1), m_count}; }
    std::span<const float> pz() const { return {array(2), m_count}; }

    /// One step of dt for every particle; `threads` 0 means all cores. The result is the same
    /// whatever the thread count: particles are independent and each is stepped the same way.
    void step(const SwarmFields& fields, std::span<const PlaneT<float>> planes, CollisionResponse response, float dt,
              int threads = 0);

    /// The first particle whose state stopped being finite in the last step, if any: every
    /// step checks each block while it is still in cache.
    struct NonFiniteParticle {
        std::size_t index;
        const char* quantity; ///< "position" or "velocity"
    };
    const std::optional<NonFiniteParticle>& nonFinite() const { return m_nonFinite; }

    /// Tells `observer` of every range the following steps finish (nullptr: stop). Not owned; a
    /// copy of the swarm starts without it, and one assigned to keeps its own.
    void setRangeObserver(SwarmRangeObserver* observer) { m_observer.observer = observer; }

    /// Times each phase of the following steps into `times` (nullptr: stop).
    void setPhaseTimes(SwarmPhaseTimes* times) { m_phaseTimes = times; }

    /// A copy of every particle's state, for a World that rolls a failed step back, and back.
    void saveState(std::vector<float>& out) const { out.assign(m_state.begin(), m_state.end()); }
    void restoreState(const std::vector<float>& saved)
    {
        std::copy(saved.begin(), saved.end(), m_state.begin());
        m_nonFinite.reset();
    }

private:
    void stepRange(const SwarmKernelFields& fields, std::span<const PlaneT<float>> planes, CollisionResponse response,
                   float dt, std::size_t begin, std::size_t end);
    void stepAll(const SwarmKernelFields& fields, std::span<const PlaneT<float>> planes, CollisionResponse response,
                 float dt, int threads);
    void findNonFinite();

    SwarmDesc m_desc;
    float m_mass;
    float m_restitution;
    Integrator m_integrator;
    /// Component c's array (x, y, z, vx, vy, vz): all six in one allocation, see m_state.
    const float* array(int c) const { return m_state.data() + std::size_t(c) * m_stride; }
    float* array(int c) { return m_state.data() + std::size_t(c) * m_stride; }

    /// Floats from one array to the next for `count` particles: whole 4 KB pages, so that each
    /// array starts on a page. Staggering them by 576 bytes more (against 4K aliasing between
    /// element k of the six) measured no faster on a quiet machine (docs/performance.md).
    static constexpr std::size_t strideFor(std::size_t count)
    {
        constexpr std::size_t kPage = 4096 / sizeof(float);
        return (count + kPage - 1) / kPage * kPage;
    }

    std::size_t m_count = 0;
    std::size_t m_stride = 0; ///< strideFor(m_count)
    /// Cache-line aligned (every 16-float vector of the loop is one line), in huge pages where the
    /// kernel has them (see LargeArrayAllocator).
    LargeArray<float> m_state;
    std::optional<NonFiniteParticle> m_nonFinite;
    SwarmPhaseTimes* m_phaseTimes = nullptr; ///< not owned; not copied meaningfully (a copy times into the same)
    /// Not owned, and not carried by a copy or an assignment: it watches this object's steps.
    struct ObserverSlot {
        SwarmRangeObserver* observer = nullptr;
        ObserverSlot() = default;
        ObserverSlot(const ObserverSlot&) {}
        ObserverSlot& operator=(const ObserverSlot&) { return *this; }
    } m_observer;
    /// What a step keeps for the next besides the state (per-block hints, the exact response's
    /// flags): swarm.cpp's. None of it changes a result.
    struct StepMemory;
    ClonePtr<StepMemory> m_memory;
};

} // namespace pba
