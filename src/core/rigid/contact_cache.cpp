#include "rigid/contact_cache.hpp"

#include <algorithm>

namespace pba::rigid {

void ContactCache::beginStep()
{
    std::swap(m_previous, m_current);
    m_current.clear();
    m_previousKeys.resize(m_previous.size());
    for (std::size_t k = 0; k < m_previous.size(); ++k)
        m_previousKeys[k] = {m_previous[k].key(), std::uint32_t(k)};
    // The list is a few sorted runs (the pairs, the room's contacts, a sleeping pile's carried
    // over): merged run by run rather than sorted anew, unless there are many.
    constexpr int kMostRuns = 8;
    int runs = 0;
    const auto begin = m_previousKeys.begin(), end = m_previousKeys.end();
    for (auto it = begin; it != end && runs <= kMostRuns; ++runs)
        it = std::is_sorted_until(it, end);
    if (runs > kMostRuns) {
        std::sort(begin, end);
        return;
    }
    for (auto it = std::is_sorted_until(begin, end); it != end;) {
        const auto next = std::is_sorted_until(it, end);
        std::inplace_merge(begin, it, next);
        it = next;
    }
}

const Contact* ContactCache::previous(std::uint64_t key) const
{
    const auto it = std::lower_bound(m_previousKeys.begin(), m_previousKeys.end(), std::make_pair(key, std::uint32_t(0)));
    return it != m_previousKeys.end() && it->first == key ? &m_previous[it->second] : nullptr;
}

void ContactCache::warmStart(Contact& c) const { warmStart(c, previous(c.key())); }

void ContactCache::warmStart(Contact& c, const Contact* old) const
{
    if (!old)
        return;
    // By feature id first; a point whose features changed (a clipped corner of a box resting
    // exactly on another, whose side planes it sits on, is a vertex one step and an edge's
    // crossing the next) takes the impulses of the nearest unclaimed old point within
    // kMatchDistance on both bodies, as Jolt matches its cached points by position.
    constexpr double kMatchDistance = 0.01;
    bool claimed[contact::Manifold::kMaxPoints] = {};
    bool matched[contact::Manifold::kMaxPoints] = {};
    auto take = [&](ContactPoint& p, int j) {
        p.normalImpulse = old->points[j].normalImpulse;
        p.tangentImpulse[0] = old->points[j].tangentImpulse[0];
        p.tangentImpulse[1] = old->points[j].tangentImpulse[1];
        claimed[j] = true;
    };
    for (int i = 0; i < c.count; ++i)
        for (int j = 0; j < old->count; ++j)
            if (!claimed[j] && old->points[j].id == c.points[i].id) {
                take(c.points[i], j);
                matched[i] = true;
                break;
            }
    for (int i = 0; i < c.count; ++i) {
        if (matched[i])
            continue;
        int best = -1;
        double nearest = kMatchDistance * kMatchDistance;
        for (int j = 0; j < old->count; ++j) {
            if (claimed[j])
                continue;
            const double d = std::max(glm::dot(old->points[j].anchorA - c.points[i].anchorA,
                                               old->points[j].anchorA - c.points[i].anchorA),
                                      glm::dot(old->points[j].anchorB - c.points[i].anchorB,
                                               old->points[j].anchorB - c.points[i].anchorB));
            if (d < nearest) {
                nearest = d;
                best = j;
            }
        }
        if (best >= 0)
            take(c.points[i], best);
    }
}

void ContactCache::clear()
{
    m_current.clear();
    m_previous.clear();
    m_previousKeys.clear();
}

} // namespace pba::rigid
