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
    std::sort(m_previousKeys.begin(), m_previousKeys.end());
}

const Contact* ContactCache::previous(std::uint64_t key) const
{
    const auto it = std::lower_bound(m_previousKeys.begin(), m_previousKeys.end(), std::make_pair(key, std::uint32_t(0)));
    return it != m_previousKeys.end() && it->first == key ? &m_previous[it->second] : nullptr;
}

void ContactCache::warmStart(Contact& c) const
{
    const Contact* old = previous(c.key());
    if (!old)
        return;
    for (int i = 0; i < c.count; ++i) {
        ContactPoint& p = c.points[i];
        for (int j = 0; j < old->count; ++j)
            if (old->points[j].id == p.id) {
                p.normalImpulse = old->points[j].normalImpulse;
                p.tangentImpulse[0] = old->points[j].tangentImpulse[0];
                p.tangentImpulse[1] = old->points[j].tangentImpulse[1];
                break;
            }
    }
}

void ContactCache::clear()
{
    m_current.clear();
    m_previous.clear();
    m_previousKeys.clear();
}

} // namespace pba::rigid
