#include "study/jet_watch.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

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

/// Only particles below the nozzle can be under the hole, and few are (a tenth of a percent of
/// fountain-1m's): each chunk of the swarm is first asked, in a vectorised pass over the heights
/// alone, whether it holds one, and the list of the particles under the hole is made again from
/// those chunks, each carrying its count of steps from the last list (both in index order). A
/// counter per particle, read and written every step beside all three coordinates, made this
/// watch 40% of `pba sim fountain-1m`'s time, more than the swarm's steps on both cores.
void JetWatch::countStepsInShaft(const World& world)
{
    constexpr std::size_t kChunk = 64;
    const BlowDryerKernelT<float> kernel(m_field->as<float>());
    const float nx = kernel.nozzle.x, ny = kernel.nozzle.y, nz = kernel.nozzle.z;
    for (std::size_t s = 0; s < world.swarmCount(); ++s) {
        const Swarm& swarm = world.swarm(s);
        const float* px = swarm.px().data();
        const float* py = swarm.py().data();
        const float* pz = swarm.pz().data();
        const std::vector<ShaftStay>& before = m_inShaft[s];
        m_nextInShaft.clear();
        std::size_t k = 0; // the first of `before` not yet passed
        std::uint32_t longest = m_longestSteps[s];
        for (std::size_t c = 0; c < swarm.size(); c += kChunk) {
            const std::size_t end = std::min(swarm.size(), c + kChunk);
            std::uint32_t below = 0;
            for (std::size_t i = c; i < end; ++i)
                below += static_cast<std::uint32_t>(py[i] - ny < 0.0f);
            for (std::size_t i = c; below > 0 && i < end; ++i) {
                // x and z read only below the nozzle (their cache lines are not the pass's).
                const float height = py[i] - ny;
                if (!(height < 0.0f))
                    continue;
                const float dx = px[i] - nx, dz = pz[i] - nz;
                if (!inBlowDryerShaft(kernel, height, dx * dx + dz * dz))
                    continue;
                while (k < before.size() && before[k].index < i)
                    ++k;
                const std::uint32_t steps = (k < before.size() && before[k].index == i ? before[k].steps : 0u) + 1u;
                m_nextInShaft.push_back({i, steps});
                longest = std::max(longest, steps);
            }
        }
        m_inShaft[s].swap(m_nextInShaft);
        m_longestSteps[s] = longest;
        m_swarms[s].longestInShaft = double(longest) * (world.time() - world.previousTime());
    }
}

void JetWatch::lookAtSwarms(const World& world)
{
    if (world.time() < m_nextLook - 1e-9)
        return;
    m_nextLook = world.time() + kSwarmSample;
    for (std::size_t s = 0; s < world.swarmCount(); ++s) {
        const Swarm& swarm = world.swarm(s);
        std::size_t inCone = 0;
        for (std::size_t i = 0; i < swarm.size(); ++i)
            inCone += insideBlowDryerCone(*m_field, dvec3(swarm.position(i))) ? 1 : 0;
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
