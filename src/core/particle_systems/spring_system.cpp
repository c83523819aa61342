#include "particle_systems/spring_system.hpp"

#include "pba/forces.hpp"
#include "pba/spring_network.hpp"

namespace pba::detail {

namespace {

/// Hands every spring of a force to the system, and says whether the force was one.
class Gatherer final : public ForceVisitor {
public:
    explicit Gatherer(SpringSystem& system) : m_system(system) {}
    bool found = false;

    void visit(const Spring& s) override
    {
        found = true;
        const dvec3 anchor = s.anchor();
        m_system.addSpring(s.particle(), 0, s.stiffness(), s.restLength(), s.damping(), &anchor);
    }
    void visit(const TwoBodySpring& s) override
    {
        found = true;
        m_system.addSpring(s.first(), s.second(), s.stiffness(), s.restLength(), s.damping(), nullptr);
    }
    void visit(const SpringNetwork& springs) override
    {
        found = true;
        for (std::size_t s = 0; s < springs.size(); ++s) {
            const SpringNetwork::Link l = springs.link(s);
            m_system.addSpring(l.a, l.b, l.stiffness, l.restLength, l.damping, nullptr);
        }
    }

private:
    SpringSystem& m_system;
};

} // namespace

SpringSystem::SpringSystem(std::span<const ClonePtr<Force>> forces, std::span<const std::size_t> members,
                           std::size_t bodyCount)
    : m_bodies(members.size())
{
    m_local.assign(bodyCount, kFixed);
    for (std::size_t k = 0; k < members.size(); ++k)
        m_local[members[k]] = static_cast<std::uint32_t>(k);
    Gatherer gatherer(*this);
    m_isSpring.assign(forces.size(), 0);
    for (std::size_t f = 0; f < forces.size(); ++f) {
        gatherer.found = false;
        forces[f]->accept(gatherer);
        m_isSpring[f] = gatherer.found ? 1 : 0;
    }
    m_local.clear();
    m_local.shrink_to_fit();
    buildIncidence();
}

void SpringSystem::addSpring(std::size_t a, std::size_t b, double k, double rest, double c, const dvec3* anchor)
{
    // A rigid body's spring (an anchored spring tied to a point of it) has no member end: it
    // falls out here with every spring of another system.
    const std::uint32_t la = a < m_local.size() ? m_local[a] : kFixed;
    const std::uint32_t lb = anchor || b >= m_local.size() ? kFixed : m_local[b];
    if (la == kFixed && lb == kFixed)
        return;
    const bool fixedSecond = lb == kFixed;
    m_a.push_back(la == kFixed ? lb : la); // the member first: a spring is the same either way round
    m_b.push_back(la == kFixed || fixedSecond ? kFixed : lb);
    m_stiffness.push_back(k);
    m_rest.push_back(rest);
    m_damping.push_back(c);
    if (la == kFixed || fixedSecond) {
        m_fixedEnd.push_back(static_cast<std::uint32_t>(m_fixedPoint.size()));
        m_fixedBody.push_back(anchor ? kAnchor : la == kFixed ? a : b);
        m_fixedPoint.push_back(anchor ? *anchor : dvec3(0.0));
    } else {
        m_fixedEnd.push_back(kFixed);
    }
}

SpringSystem SpringSystem::withExtraMembers(std::size_t extra, std::span<const LocalSpring> springs) const
{
    SpringSystem joined = *this;
    joined.m_bodies += extra;
    for (const LocalSpring& s : springs) {
        joined.m_a.push_back(s.a);
        joined.m_b.push_back(s.b);
        joined.m_stiffness.push_back(s.stiffness);
        joined.m_rest.push_back(s.rest);
        joined.m_damping.push_back(s.damping);
        joined.m_fixedEnd.push_back(kFixed);
    }
    joined.buildIncidence();
    return joined;
}

void SpringSystem::setLastSprings(std::span<const LocalSpring> springs)
{
    const std::size_t first = size() - springs.size();
    for (std::size_t i = 0; i < springs.size(); ++i) {
        m_stiffness[first + i] = springs[i].stiffness;
        m_rest[first + i] = springs[i].rest;
        m_damping[first + i] = springs[i].damping;
    }
}

void SpringSystem::placeFixedEnds(std::span<const dvec3> positions)
{
    for (std::size_t e = 0; e < m_fixedBody.size(); ++e)
        if (m_fixedBody[e] != kAnchor)
            m_fixedPoint[e] = positions[m_fixedBody[e]];
}

void SpringSystem::buildIncidence()
{
    // Counting sort, as SpringNetwork's: member p's springs in the springs' order.
    m_first.assign(m_bodies + 1, 0);
    for (std::size_t s = 0; s < size(); ++s) {
        ++m_first[m_a[s] + 1];
        if (m_b[s] != kFixed)
            ++m_first[m_b[s] + 1];
    }
    for (std::size_t p = 0; p < m_bodies; ++p)
        m_first[p + 1] += m_first[p];
    m_incident.resize(m_first[m_bodies]);
    std::vector<std::uint32_t> next(m_first.begin(), m_first.end() - 1);
    for (std::size_t s = 0; s < size(); ++s) {
        m_incident[next[m_a[s]]++] = static_cast<std::uint32_t>(2 * s);
        if (m_b[s] != kFixed)
            m_incident[next[m_b[s]]++] = static_cast<std::uint32_t>(2 * s + 1);
    }
}

} // namespace pba::detail
