#include "study/jet_watch.hpp"

#include "pba/detail/instruction_sets.hpp"

#include <algorithm>
#include <bit>
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

/// For each chunk of kChunk heights from y (the last may be short), whether one may be below
/// `level`: the sign bits of y - level ORed together (a NaN may be flagged; the exact test
/// follows). The watch's pass costs the instructions of this loop, not memory (in the attached
/// watch the heights are in cache): one instruction a vector where a compare and a count took
/// three, on the widest vectors the CPU has.
PBA_TARGET_CLONES
void flagChunksBelow(const float* __restrict y, std::size_t n, float level, std::uint8_t* __restrict flags)
{
    for (std::size_t c = 0; c * kChunk < n; ++c) {
        const std::size_t end = std::min(n, (c + 1) * kChunk);
        std::uint32_t signs = 0;
        for (std::size_t i = c * kChunk; i < end; ++i)
            signs |= std::bit_cast<std::uint32_t>(y[i] - level);
        flags[c] = static_cast<std::uint8_t>(signs >> 31);
    }
}

/// Particles from begin to end under the hole, each with its steps in a row there (one more
/// than in `before`, the last step's list in index order).
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
    std::uint8_t below[kSegment / kChunk];
    for (std::size_t s = begin; s < end; s += kSegment) {
        const std::size_t segmentEnd = std::min(end, s + kSegment);
        flagChunksBelow(py + s, segmentEnd - s, ny, below);
        for (std::size_t c = s; c < segmentEnd; c += kChunk) {
            if (below[(c - s) / kChunk] == 0)
                continue;
            for (std::size_t i = c; i < std::min(segmentEnd, c + kChunk); ++i) {
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
}

} // namespace

/// A swarm's particles under the hole, listed range by range as the step finishes each (any
/// thread, any order; each range writes only its own piece), then joined in index order.
class ShaftLister final : public SwarmRangeObserver {
public:
    /// Ranges are whole blocks of this many particles (SwarmRangeObserver).
    static constexpr std::size_t kBlock = 512;

    ShaftLister(const BlowDryerKernelT<float>& kernel, const std::vector<JetWatch::ShaftStay>& before, std::size_t n)
        : m_kernel(kernel), m_before(before), m_pieces(n / kBlock + 1)
    {
    }

    void stepped(const Swarm& swarm, std::size_t begin, std::size_t end) override
    {
        if (begin % kBlock != 0 || begin / kBlock >= m_pieces.size())
            return; // not a range this lister was made for: collect finds it missing
        Piece& piece = m_pieces[begin / kBlock];
        listInShaft(swarm, m_kernel, begin, end, m_before, piece.list);
        piece.end = end;
        piece.generation = m_generation;
    }

    /// This step's list, if every range of the swarm's n particles was told of in it.
    bool collect(std::size_t n, std::vector<JetWatch::ShaftStay>& out)
    {
        const std::uint64_t now = m_generation++;
        out.clear();
        for (std::size_t begin = 0; begin < n;) {
            if (begin / kBlock >= m_pieces.size() || m_pieces[begin / kBlock].generation != now)
                return false;
            const Piece& piece = m_pieces[begin / kBlock];
            out.insert(out.end(), piece.list.begin(), piece.list.end());
            begin = piece.end;
        }
        return true;
    }

private:
    struct Piece {
        std::uint64_t generation = 0;
        std::size_t end = 0;
        std::vector<JetWatch::ShaftStay> list;
    };
    BlowDryerKernelT<float> m_kernel;
    const std::vector<JetWatch::ShaftStay>& m_before; ///< the last step's list, the watch's
    std::vector<Piece> m_pieces;                      ///< by the range's first block
    std::uint64_t m_generation = 1;
};

namespace {

/// Where x lies against the cone, in floats: kMaybe wherever insideBlowDryerCone (in double) is
/// true, and kSurely only where it is, each by a margin far above the floats' rounding, so only
/// the particles near the cone's surface take the exact test.
constexpr std::uint32_t kMaybe = 1, kSurely = 2;
std::uint32_t placeInCone(const BlowDryerKernelT<float>& kernel, float margin, const Vec3<float>& x)
{
    const auto [d, h, rho, r2, across2] = DryerFrameT<DryerAxis::Any, float>(kernel.nozzle, kernel.axis, x);
    const float slack = margin * (1.0f + std::abs(d.x) + std::abs(d.y) + std::abs(d.z));
    const float s = std::min(std::max(h, 0.0f), kernel.height) * kernel.inverseHeight;
    const float q = std::max(kernel.nozzleRadius + kernel.spread * s, 0.0f);
    const float outer = q + slack, inner = q - slack;
    const std::uint32_t maybe = (h > -slack) & (h < kernel.height + slack) & (r2 < outer * outer);
    const std::uint32_t surely = (h > slack) & (h < kernel.height - slack) & (inner > 0.0f) & (r2 < inner * inner);
    return maybe * kMaybe | surely * kSurely;
}

} // namespace

/// Only particles below the nozzle can be under the hole, and few are (a tenth of a percent of
/// fountain-1m's): each chunk of the swarm is first asked, in a vectorised pass over the heights
/// alone, whether it holds one, and the list of the particles under the hole is made again from
/// those chunks, each carrying its count of steps from the last list (both in index order): by
/// the swarm's own step, range by range, while attached; else a segment of the swarm at a time on
/// all cores. (A counter per particle, read and written every step beside all three
/// coordinates, made this watch 40% of `pba sim fountain-1m`'s time.)
void JetWatch::countStepsInShaft(const World& world)
{
    const BlowDryerKernelT<float> kernel(m_field->as<float>());
    for (std::size_t s = 0; s < world.swarmCount(); ++s) {
        const Swarm& swarm = world.swarm(s);
        std::vector<ShaftStay>& inShaft = m_inShaft[s];
        if (s < m_listers.size() && m_listers[s] && m_listers[s]->collect(swarm.size(), m_listed)) {
            inShaft.swap(m_listed);
            ++m_listedInStep;
            noteLongest(world, s);
            continue;
        }
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
        noteLongest(world, s);
    }
}

void JetWatch::noteLongest(const World& world, std::size_t s)
{
    for (const ShaftStay& stay : m_inShaft[s])
        m_longestSteps[s] = std::max(m_longestSteps[s], stay.steps);
    m_swarms[s].longestInShaft = double(m_longestSteps[s]) * (world.time() - world.previousTime());
}

/// Swarms whose grains collide are moved again after their step's ranges (World's grain
/// contacts): their lists are made afterwards, as without an attachment.
JetWatch::Attachment JetWatch::attach(World& world)
{
    if (!m_field || !m_field->shaft)
        return Attachment(nullptr);
    const BlowDryerKernelT<float> kernel(m_field->as<float>());
    m_listers.clear();
    m_listers.resize(world.swarmCount());
    for (std::size_t s = 0; s < world.swarmCount(); ++s) {
        Swarm& swarm = world.swarm(s);
        if (swarm.desc().collide)
            continue;
        m_listers[s] = std::make_unique<ShaftLister>(kernel, m_inShaft[s], swarm.size());
        swarm.setRangeObserver(m_listers[s].get());
    }
    return Attachment(&world);
}

JetWatch::Attachment::~Attachment()
{
    if (m_world)
        for (std::size_t s = 0; s < m_world->swarmCount(); ++s)
            m_world->swarm(s).setRangeObserver(nullptr);
}

JetWatch::JetWatch(JetWatch&&) noexcept = default;
JetWatch& JetWatch::operator=(JetWatch&&) noexcept = default;
JetWatch::~JetWatch() = default;

/// The cone's count, every kSwarmSample: insideBlowDryerCone in double for the particles a test
/// in floats can neither rule in nor out (those within rounding of the cone's surface), a
/// segment at a time on all cores (a sum of counts: the same in any order).
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
                    std::uint32_t place[kChunk]; // a vectorised pass in floats first, the few in double after
                    std::uint32_t surely = 0, unsure = 0;
                    for (std::size_t j = 0; j < n; ++j)
                        place[j] = placeInCone(kernel, margin, Vec3<float>(px[c + j], py[c + j], pz[c + j]));
                    for (std::size_t j = 0; j < n; ++j) {
                        surely += place[j] / kSurely;
                        unsure += place[j] == kMaybe;
                    }
                    count += surely;
                    for (std::size_t j = 0; unsure > 0 && j < n; ++j)
                        if (place[j] == kMaybe)
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
            const dvec3 d = x - dvec3(m_field->nozzle), axis(m_field->axis);
            t.offAxisTime += glm::length(d - glm::dot(d, axis) * axis) * dt;
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
        const double none = std::numeric_limits<double>::quiet_NaN();
        b.meanHeightInCone = b.timeInCone > 0.0 ? t.heightTime / b.timeInCone : none;
        b.meanOffAxisInCone = b.timeInCone > 0.0 ? t.offAxisTime / b.timeInCone : none;
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
