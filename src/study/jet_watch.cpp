#include "study/jet_watch.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

namespace pba::study {

JetWatch::JetWatch(const World& world)
{
    if (const auto dryers = blowDryers(world); !dryers.empty())
        m_field = dryers.front().field;
    if (!m_field)
        return;
    const double g = glm::length(world.gravity());
    for (std::size_t i = 0; i < world.bodyCount(); ++i) {
        Track t;
        t.figures.name = world.body(i).getName();
        t.figures.mass = world.body(i).getMass();
        t.figures.liftable = !world.body(i).isFixed() && m_field->strength > t.figures.mass * g;
        m_tracks.push_back(t);
    }
    m_swarms.resize(world.swarmCount());
    m_longestSteps.assign(world.swarmCount(), 0);
    m_inShaft.resize(world.swarmCount());
    lookAtSwarms(world);
}

namespace {

/// The watch's passes split a swarm into segments of this many particles (whole 64-particle
/// chunks), stepped on all cores: the same segments whatever the thread count, so the lists
/// they make are joined in the same order.
constexpr std::size_t kSegment = 8192;
constexpr std::size_t kChunk = 64;

std::size_t segmentCount(std::size_t particles) { return (particles + kSegment - 1) / kSegment; }

/// Particles of a segment under the hole, each with its steps in a row there (one more than in
/// `before`, the last step's list in index order).
void listInShaft(const Swarm& swarm, const BlowDryerKernelT<float>& kernel, std::size_t begin, std::size_t end,
                 const std::vector<JetWatch::ShaftStay>& before, std::vector<JetWatch::ShaftStay>& out)
{
    const float* px = swarm.px().data();
    const float* py = swarm.py().data();
    const float* pz = swarm.pz().data();
    const float nx = kernel.nozzle.x, ny = kernel.nozzle.y, nz = kernel.nozzle.z;
    auto k = std::lower_bound(before.begin(), before.end(), begin,
                              [](const JetWatch::ShaftStay& stay, std::size_t i) { return stay.index < i; });
    out.clear();
    for (std::size_t c = begin; c < end; c += kChunk) {
        const std::size_t chunkEnd = std::min(end, c + kChunk);
        std::uint32_t below = 0;
        for (std::size_t i = c; i < chunkEnd; ++i)
            below += static_cast<std::uint32_t>(py[i] - ny < 0.0f);
        for (std::size_t i = c; below > 0 && i < chunkEnd; ++i) {
            // x and z read only below the nozzle (their cache lines are not the pass's).
            const float height = py[i] - ny;
            if (!(height < 0.0f))
                continue;
            const float dx = px[i] - nx, dz = pz[i] - nz;
            if (!inBlowDryerShaft(kernel, height, dx * dx + dz * dz))
                continue;
            while (k != before.end() && k->index < i)
                ++k;
            const std::uint32_t steps = (k != before.end() && k->index == i ? k->steps : 0u) + 1u;
            out.push_back({i, steps});
        }
    }
}

/// Whether x may be in the cone, in floats: true wherever insideBlowDryerCone (in double) is,
/// by a margin far above the floats' rounding, so only these particles take the exact test.
bool mayBeInCone(const BlowDryerKernelT<float>& kernel, float margin, const Vec3<float>& x)
{
    const auto [d, h, rho, r2, across2] = DryerFrameT<DryerAxis::Any, float>(kernel.nozzle, kernel.axis, x);
    const float slack = margin * (1.0f + std::abs(d.x) + std::abs(d.y) + std::abs(d.z));
    const float s = std::min(std::max(h, 0.0f), kernel.height) * kernel.inverseHeight;
    const float q = std::max(kernel.nozzleRadius + kernel.spread * s, 0.0f) + slack;
    return (h > -slack) & (h < kernel.height + slack) & (r2 < q * q);
}

} // namespace

/// Only particles below the nozzle can be under the hole, and few are (a tenth of a percent of
/// fountain-1m's): each chunk of the swarm is first asked, in a vectorised pass over the heights
/// alone, whether it holds one, and the list of the particles under the hole is made again from
/// those chunks, each carrying its count of steps from the last list (both in index order), a
/// segment of the swarm at a time on all cores. (A counter per particle, read and written every
/// step beside all three coordinates, made this watch 40% of `pba sim fountain-1m`'s time.)
void JetWatch::countStepsInShaft(const World& world)
{
    const BlowDryerKernelT<float> kernel(m_field->as<float>());
    for (std::size_t s = 0; s < world.swarmCount(); ++s) {
        const Swarm& swarm = world.swarm(s);
        std::vector<ShaftStay>& inShaft = m_inShaft[s];
        const std::size_t segments = segmentCount(swarm.size());
        m_segmentLists.resize(std::max(m_segmentLists.size(), segments));
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, segments), [&](const tbb::blocked_range<std::size_t>& r) {
            for (std::size_t g = r.begin(); g != r.end(); ++g)
                listInShaft(swarm, kernel, g * kSegment, std::min(swarm.size(), (g + 1) * kSegment), inShaft,
                            m_segmentLists[g]);
        });
        inShaft.clear(); // the last step's list, read by every segment, is done with
        for (std::size_t g = 0; g < segments; ++g)
            inShaft.insert(inShaft.end(), m_segmentLists[g].begin(), m_segmentLists[g].end());
        for (const ShaftStay& stay : inShaft)
            m_longestSteps[s] = std::max(m_longestSteps[s], stay.steps);
        m_swarms[s].longestInShaft = double(m_longestSteps[s]) * (world.time() - world.previousTime());
    }
}

/// The cone's count, every kSwarmSample: insideBlowDryerCone in double for the particles a test
/// in floats cannot rule out (a quarter of them while rain falls through the cone, about 1% once
/// it has landed), a segment at a time on all cores (a sum of counts: the same in any order).
void JetWatch::lookAtSwarms(const World& world)
{
    if (world.time() < m_nextLook - 1e-9)
        return;
    m_nextLook = world.time() + kSwarmSample;
    const BlowDryerKernelT<float> kernel(m_field->as<float>());
    const float margin = 1e-4f * (1.0f + std::abs(kernel.nozzle.x) + std::abs(kernel.nozzle.y) +
                                  std::abs(kernel.nozzle.z) + kernel.height + std::abs(float(m_field->topRadius)));
    for (std::size_t s = 0; s < world.swarmCount(); ++s) {
        const Swarm& swarm = world.swarm(s);
        const std::size_t inCone = tbb::parallel_reduce(
            tbb::blocked_range<std::size_t>(0, segmentCount(swarm.size())), std::size_t{0},
            [&](const tbb::blocked_range<std::size_t>& r, std::size_t count) {
                const float* px = swarm.px().data();
                const float* py = swarm.py().data();
                const float* pz = swarm.pz().data();
                const std::size_t end = std::min(swarm.size(), r.end() * kSegment);
                for (std::size_t c = r.begin() * kSegment; c < end; c += kChunk) {
                    const std::size_t n = std::min(kChunk, end - c);
                    std::uint32_t may[kChunk]; // a vectorised pass in floats first, the few in double after
                    for (std::size_t j = 0; j < n; ++j)
                        may[j] = mayBeInCone(kernel, margin, Vec3<float>(px[c + j], py[c + j], pz[c + j]));
                    for (std::size_t j = 0; j < n; ++j)
                        if (may[j] != 0)
                            count += insideBlowDryerCone(*m_field, dvec3(px[c + j], py[c + j], pz[c + j])) ? 1 : 0;
                }
                return count;
            },
            std::plus<>());
        SwarmInJet& figures = m_swarms[s];
        if (inCone > figures.peakInCone) {
            figures.peakInCone = inCone;
            figures.peakAt = world.time();
        }
    }
}

void JetWatch::record(const World& world)
{
    if (!m_field)
        return;
    // A step's time counts where the body is at its end: the figures are sums over steps.
    const double dt = world.time() - world.previousTime();
    m_watched += dt;
    for (std::size_t i = 0; i < m_tracks.size(); ++i) {
        Track& t = m_tracks[i];
        const dvec3& x = world.body(i).getPos();
        if (insideBlowDryerCone(*m_field, x)) {
            if (t.stay == 0.0)
                t.stayStart = world.previousTime();
            t.stay += dt;
            t.figures.timeInCone += dt;
            t.heightTime += x.y * dt;
            t.figures.longestStay = std::max(t.figures.longestStay, t.stay);
            if (!t.figures.caughtAt && t.stay >= kCatchStay - 1e-9)
                t.figures.caughtAt = t.stayStart;
        } else {
            t.stay = 0.0;
        }
        t.shaftStay = insideBlowDryerShaft(*m_field, x) ? t.shaftStay + dt : 0.0;
        t.figures.longestInShaft = std::max(t.figures.longestInShaft, t.shaftStay);
    }
    if (world.swarmCount() > 0 && m_field->shaft) {
        countStepsInShaft(world);
        lookAtSwarms(world);
    }
}

std::vector<BodyInJet> JetWatch::bodies() const
{
    std::vector<BodyInJet> result;
    for (const Track& t : m_tracks) {
        BodyInJet b = t.figures;
        b.meanHeightInCone = b.timeInCone > 0.0 ? t.heightTime / b.timeInCone : std::numeric_limits<double>::quiet_NaN();
        result.push_back(b);
    }
    return result;
}

double JetWatch::fractionInCone(std::size_t i) const
{
    return m_watched > 0.0 ? m_tracks[i].figures.timeInCone / m_watched : 0.0;
}

std::vector<std::size_t> JetWatch::swarmsInShaft(const World& world) const
{
    std::vector<std::size_t> counts;
    for (std::size_t s = 0; s < world.swarmCount(); ++s) {
        std::size_t n = 0;
        if (m_field) {
            const Swarm& swarm = world.swarm(s);
            for (std::size_t i = 0; i < swarm.size(); ++i)
                n += insideBlowDryerShaft(*m_field, dvec3(swarm.position(i))) ? 1 : 0;
        }
        counts.push_back(n);
    }
    return counts;
}

} // namespace pba::study
