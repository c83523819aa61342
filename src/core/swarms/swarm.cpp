#include "pba/swarm.hpp"

// The step's phases live in private headers, one concept each, included here alone: every
// instruction set's copy of stepSwarmRange inlines them all (see PBA_FOR_EACH_INSTRUCTION_SET).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <span>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "swarms/phase_clock.hpp"
#include "surfaces/room_surfaces.hpp"
#include "surfaces/surface_tests.hpp"
#include "swarms/swarm_block.hpp"
#include "swarms/swarm_collide.hpp"
#include "swarms/swarm_integrate.hpp"

namespace pba {

namespace {

/// splitmix64: a counter-based generator, so particle i's values depend on (seed, i) alone.
std::uint64_t mix(std::uint64_t z)
{
    z += 0x9e3779b97f4a7c15ull;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

double uniform(std::uint64_t seed, std::uint64_t i, int component)
{
    return double(mix(mix(seed) ^ mix(i * 8 + std::uint64_t(component))) >> 11) * 0x1.0p-53;
}

/// Whether a point clear of the box's walls is clear of every plane: the other planes (the
/// grille at the bottom of the hole's shaft) are clear of the whole of the box's clear region,
/// tested at its eight corners, in double precision.
bool boxCoversAll(const BoxWallsT<float>& box, std::span<const PlaneT<float>> planes)
{
    for (std::size_t p = 0; p < planes.size(); ++p) {
        if (p < 64 && (box.mask >> p & 1u) != 0)
            continue;
        const PlaneT<float>& plane = planes[p];
        for (int corner = 0; corner < 8; ++corner) {
            const double x = corner & 1 ? box.clearHi[0] : box.clearLo[0];
            const double y = corner & 2 ? box.clearHi[1] : box.clearLo[1];
            const double z = corner & 4 ? box.clearHi[2] : box.clearLo[2];
            const double d = double(plane.normal.x) * x + double(plane.normal.y) * y + double(plane.normal.z) * z -
                             double(plane.offset);
            if (!(d > 2.0 * double(collision_detail::contactTolerance(plane))))
                return false;
        }
    }
    return true;
}

/// The same surfaces: what the exact response's remembered flags were computed against.
bool samePlanes(std::span<const PlaneT<float>> a, std::span<const PlaneT<float>> b)
{
    return std::equal(a.begin(), a.end(), b.begin(), b.end(), [](const auto& p, const auto& q) {
        return p.normal == q.normal && p.offset == q.offset && p.holeRadius == q.holeRadius &&
               p.holeCentre == q.holeCentre;
    });
}

/// Below this many particles threads cost more than they save (several times slower at 1,000).
constexpr std::size_t kParallelThreshold = 32768;

/// A range's step, block by block: integrate (checking the states are finite as they are
/// written); test which particles are near a surface; the rule for those, gathered from several
/// blocks when few, over the whole block when many (passInRoom in a World's room). Against the
/// simplest design, one fused pass a block that integrates and runs the rule's first pass over
/// every surface as selects for every particle, these phases are about 1.3-1.4 times as fast in
/// flight and landed. The selects cost every particle what the surface test costs only those near a
/// surface, and one long chain a particle (roots, divisions, then the rule) leaves the
/// out-of-order core less to overlap than two short loops. Fused only where the pass runs over
/// the whole block anyway (a crowded block) it was no faster either. Loading a block from L1
/// twice is not what these loops wait on; their instructions are (docs/performance.md).
template <Integrator kIntegrator>
void stepBlocks(const Arrays& a, std::size_t begin, std::size_t end, const SwarmKernelFields& fields,
                         float restitution, float friction, float dt, std::span<const PlaneT<float>> planes,
                         CollisionResponse response)
{
    alignas(64) float start[6][kBlock];
    alignas(64) std::uint8_t hit[kBlock + 64]; // room for listHits' last word
    const std::optional<BoxWallsT<float>> box = boxWalls(planes);
    const bool coversAll = box && boxCoversAll(*box, planes);
    const bool exact = response == CollisionResponse::Exact;
    const std::optional<RoomSurfacesT<float>> room = exact ? std::nullopt : roomSurfaces(planes);
    GatheredHits gathered(a, restitution, friction, planes, response, room);
    const bool drag = fields.dragPerMass != 0.0f;
    const BlowDryerReach reach(fields.dryer, dt, glm::length(dvec3(fields.gravity)), fields.dragPerMass);
    PhaseClock clock(a.phases);
    for (std::size_t b = begin; b < end; b += kBlock) {
        const std::size_t n = std::min(kBlock, end - b);
        // Whether the states the block's loops wrote are finite: swarms are checked every step
        // like bodies, and the flags say where to look for the first bad particle. Each loop
        // that writes the states tests them while they are in registers (a pass of its own
        // over the block measured as long as the surface test).
        bool finite = integrateFor<kIntegrator>(a, b, n, dt, start, response, fields, drag, reach);
        clock.lap(SwarmPhaseTimes::Integrate);
        // A crowded block (most of it on the floor last step, as a landed swarm is) skips the
        // surface test and takes the collision pass whole, which leaves a clear particle
        // exactly as it was: the same result, without a test that would mark most of the
        // block anyway. It stays crowded while the pass moves more than a batch's worth.
        std::uint8_t& crowded = a.crowded[b / kBlock];
        const bool test = !(room && crowded);
        const std::size_t hits = !test ? n : planes.empty() ? 0 : classifyBlock(a, b, n, planes, box, coversAll, exact, hit);
        clock.lap(SwarmPhaseTimes::SurfaceTest);
        std::size_t moved = 0;
        if (hits > 0 && exact) {
            collideExactly<kIntegrator>(a, b, n, fields, restitution, friction, dt, planes, start, hit);
            finite = allFinite(a, b, n);
        } else if (hits > 0 && hits <= kGatherMax && hits < n) {
            gathered.add(b, n, hit, start); // checked again when the batch is resolved
        } else if (hits > 0) {
            collideHits(a, b, n, restitution, friction, planes, response, room, {start[0], start[1], start[2]}, finite,
                        moved);
        }
        crowded = static_cast<std::uint8_t>(moved > kGatherMax);
        clock.lap(SwarmPhaseTimes::Collide);
        a.finite[b / kBlock] = finite;
        clock.lap(SwarmPhaseTimes::Check);
    }
    gathered.collide();
    clock.lap(SwarmPhaseTimes::Collide);
}

/// Every integrator's loop for a range of particles, compiled three times: for AVX-512
/// (x86-64-v4), AVX2 with FMA (x86-64-v3) and the baseline SSE2, the best picked when the
/// program starts. The default build so runs 16 floats an instruction on a CPU that has them
/// without `-march=native`, and still runs everywhere. `flatten` inlines every kernel into each
/// copy, so the integrator, force and collision templates are compiled for that instruction set.
/// (Vector width and fused multiply-adds change the last bits of a result from one kind of CPU
/// to another; on one machine it is the same for every thread count.)
PBA_FOR_EACH_INSTRUCTION_SET
void stepSwarmRange(Integrator integrator, const Arrays& a, std::size_t begin, std::size_t end,
                             const SwarmKernelFields& fields, float restitution, float friction, float dt,
                             std::span<const PlaneT<float>> planes, CollisionResponse response)
{
    switch (integrator) {
    case Integrator::ForwardEuler:
        stepBlocks<Integrator::ForwardEuler>(a, begin, end, fields, restitution, friction, dt, planes, response);
        return;
    case Integrator::SemiImplicitEuler:
    case Integrator::ImplicitGyroscopic: // a point does not turn
    case Integrator::ImplicitEuler:      // refused by World::addSwarm: no springs to step
    case Integrator::Xpbd:
        stepBlocks<Integrator::SemiImplicitEuler>(a, begin, end, fields, restitution, friction, dt, planes, response);
        return;
    case Integrator::VelocityVerlet:
    case Integrator::Splitting: // a point does not turn
        stepBlocks<Integrator::VelocityVerlet>(a, begin, end, fields, restitution, friction, dt, planes, response);
        return;
    case Integrator::RK4:
        stepBlocks<Integrator::RK4>(a, begin, end, fields, restitution, friction, dt, planes, response);
        return;
    }
}

} // namespace

/// What a step keeps for the next besides the state: hints that change no result, and the exact
/// response's flags of which particles ended clear of every surface.
struct Swarm::StepMemory {
    std::vector<std::uint8_t> clear; ///< exact response only, per particle: clear of every surface after its last step
    std::vector<PlaneT<float>> clearOf; ///< the surfaces `clear` was computed against
    std::vector<std::uint8_t> finite;  ///< per 512-particle block: all finite after the last step
    std::vector<std::uint8_t> crowded; ///< per block: most of it met a surface last step (see stepBlocks)
    std::vector<std::uint8_t> blowing; ///< per block: steps left with the dryer busy in it (see integrateInDryer)

    std::unique_ptr<StepMemory> clone() const
    {
        auto copy = std::make_unique<StepMemory>();
        copy->clear = clear, copy->clearOf = clearOf, copy->finite = finite;
        copy->crowded = crowded, copy->blowing = blowing;
        return copy;
    }
};

Swarm::Swarm(const SwarmDesc& desc)
    : m_desc(desc), m_mass(float(desc.mass)), m_restitution(float(desc.restitution)), m_integrator(desc.integrator),
      m_count(desc.count), m_stride(strideFor(desc.count)), m_state(6 * m_stride),
      m_memory(std::make_unique<StepMemory>())
{
    for (std::size_t i = 0; i < desc.count; ++i) {
        const dvec3 x = desc.regionMin + (desc.regionMax - desc.regionMin) *
                                             dvec3(uniform(desc.seed, i, 0), uniform(desc.seed, i, 1), uniform(desc.seed, i, 2));
        const dvec3 v = desc.velocity + desc.velocityJitter * (2.0 * dvec3(uniform(desc.seed, i, 3), uniform(desc.seed, i, 4),
                                                                            uniform(desc.seed, i, 5)) -
                                                               1.0);
        set(i, Vec3<float>(x), Vec3<float>(v));
    }
}

Swarm::Swarm(const Swarm&) = default;
Swarm::Swarm(Swarm&&) noexcept = default;
Swarm& Swarm::operator=(const Swarm&) = default;
Swarm& Swarm::operator=(Swarm&&) noexcept = default;
Swarm::~Swarm() = default;

std::unique_ptr<Swarm> Swarm::clone() const { return std::make_unique<Swarm>(*this); }

void Swarm::set(std::size_t i, const Vec3<float>& x, const Vec3<float>& v)
{
    array(0)[i] = x.x, array(1)[i] = x.y, array(2)[i] = x.z;
    array(3)[i] = v.x, array(4)[i] = v.y, array(5)[i] = v.z;
    if (!m_memory->clear.empty())
        m_memory->clear[i] = 0; // unknown until the next step tests it
}

void Swarm::stepRange(const SwarmKernelFields& fields, std::span<const PlaneT<float>> planes,
                               CollisionResponse response, float dt, std::size_t begin, std::size_t end)
{
    StepMemory& m = *m_memory;
    const Arrays a{array(0),        array(1),        array(2),         array(3),          array(4), array(5),
                   m.clear.data(), m.finite.data(), m.crowded.data(), m.blowing.data(), m_phaseTimes};
    // A colliding swarm's grains rub against the room in their contacts' sweeps instead.
    const float roomFriction = m_desc.collide ? 0.0f : friction();
    stepSwarmRange(m_integrator, a, begin, end, fields, m_restitution, roomFriction, dt, planes, response);
    if (m_observer.observer)
        m_observer.observer->stepped(*this, begin, end);
}

void Swarm::step(const SwarmFields& swarmFields, std::span<const PlaneT<float>> planes, CollisionResponse response,
                 float dt, int threads)
{
    const SwarmKernelFields fields(swarmFields, 1.0f / m_mass, radius()); // once a step, not once a task
    const std::size_t n = size();
    // The remembered "clear of every surface" flags hold only for the surfaces they were
    // computed against: new surfaces (a moved hole, another room) mean testing everything again.
    StepMemory& m = *m_memory;
    const bool same = samePlanes(planes, m.clearOf);
    if (response != CollisionResponse::Exact) {
        // Reflect and clamp look at where a step ends only: no flags to keep (or to move).
        m.clear = {};
        m.clearOf.clear();
    } else if (!same || m.clear.size() != n) {
        m.clear.assign(n, std::uint8_t(0));
        m.clearOf.assign(planes.begin(), planes.end());
    }
    m.finite.resize((n + kBlock - 1) / kBlock);
    m.crowded.resize(m.finite.size()); // hints only: a stale one changes no result
    m.blowing.resize(m.finite.size());
    stepAll(fields, planes, response, dt, threads);
    findNonFinite();
}

void Swarm::findNonFinite()
{
    m_nonFinite.reset();
    const std::vector<std::uint8_t>& finite = m_memory->finite;
    for (std::size_t block = 0; block < finite.size(); ++block) {
        if (finite[block])
            continue;
        for (std::size_t i = block * kBlock; i < std::min(m_count, (block + 1) * kBlock); ++i) {
            const Vec3<float> x = position(i), v = velocity(i);
            if (!(std::isfinite(x.x) && std::isfinite(x.y) && std::isfinite(x.z)))
                m_nonFinite = NonFiniteParticle{i, "position"};
            else if (!(std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z)))
                m_nonFinite = NonFiniteParticle{i, "velocity"};
            if (m_nonFinite)
                return;
        }
    }
}

/// TBB's default partitioner hands blocks to whichever thread is free. A static split (each
/// thread a fixed half) was slower: a thread that the machine delays holds up the step. Handing
/// each thread the blocks it had last step (TBB's affinity_partitioner) gained at most 4%
/// (docs/performance.md).
void Swarm::stepAll(const SwarmKernelFields& fields, std::span<const PlaneT<float>> planes, CollisionResponse response,
                    float dt, int threads)
{
    const std::size_t n = size();
    if (threads == 1 || n < kParallelThreshold)
        return stepRange(fields, planes, response, dt, 0, n);
    // Whole blocks per task; a particle's result does not depend on which thread steps it.
    const std::size_t blocks = (n + kBlock - 1) / kBlock;
    auto body = [&] {
        tbb::parallel_for(
            tbb::blocked_range<std::size_t>(0, blocks, 16),
            [&](const tbb::blocked_range<std::size_t>& r) {
                stepRange(fields, planes, response, dt, r.begin() * kBlock, std::min(n, r.end() * kBlock));
            });
    };
    if (threads <= 0 || threads >= tbb::this_task_arena::max_concurrency())
        return body(); // all cores: the default arena, not a new one every step
    tbb::task_arena arena(threads);
    return arena.execute(body);
}

} // namespace pba
