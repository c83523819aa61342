#include "rigid/islands.hpp"

namespace pba::rigid {

std::uint32_t Islands::find(std::uint32_t i)
{
    while (m_parent[i] != i) {
        m_parent[i] = m_parent[m_parent[i]]; // path halving
        i = m_parent[i];
    }
    return i;
}

void Islands::build(std::span<const Motion> motion, std::span<const Contact> contacts, std::span<const Link> links)
{
    const std::size_t n = motion.size();
    m_parent.resize(n);
    for (std::uint32_t i = 0; i < n; ++i)
        m_parent[i] = i;
    auto unite = [&](BodyIndex a, BodyIndex b) {
        if (a >= n || b >= n || motion[a] != Motion::Awake || motion[b] != Motion::Awake)
            return;
        std::uint32_t ra = find(a), rb = find(b);
        if (ra != rb)
            m_parent[std::max(ra, rb)] = std::min(ra, rb); // the root is the lowest index
    };
    for (const Contact& c : contacts)
        if (c.count > 0)
            unite(c.a, c.b);
    for (const Link& l : links)
        unite(l.a, l.b);

    // Number the islands by their lowest body, then bucket bodies, contacts and links.
    m_islandOf.assign(n, npos);
    std::uint32_t islands = 0;
    for (std::uint32_t i = 0; i < n; ++i)
        if (motion[i] == Motion::Awake)
            m_islandOf[i] = find(i) == i ? islands++ : m_islandOf[find(i)];
    auto bucket = [&](std::vector<std::uint32_t>& items, std::vector<std::uint32_t>& start, std::size_t count,
                      auto&& islandOfItem) {
        start.assign(islands + 1, 0);
        for (std::size_t k = 0; k < count; ++k)
            if (const std::uint32_t is = islandOfItem(k); is != npos)
                ++start[is + 1];
        for (std::uint32_t k = 0; k < islands; ++k)
            start[k + 1] += start[k];
        items.resize(start[islands]);
        std::vector<std::uint32_t> next(start.begin(), start.end() - 1);
        for (std::size_t k = 0; k < count; ++k)
            if (const std::uint32_t is = islandOfItem(k); is != npos)
                items[next[is]++] = std::uint32_t(k);
    };
    // A contact or link belongs to the island of its movable body (a static one has none).
    auto islandOfPair = [&](BodyIndex a, BodyIndex b) {
        if (a < n && m_islandOf[a] != npos)
            return m_islandOf[a];
        return b < n ? m_islandOf[b] : npos;
    };
    bucket(m_bodies, m_bodyStart, n, [&](std::size_t i) { return m_islandOf[i]; });
    bucket(m_contacts, m_contactStart, contacts.size(), [&](std::size_t k) {
        return contacts[k].count > 0 ? islandOfPair(contacts[k].a, contacts[k].b) : npos;
    });
    bucket(m_links, m_linkStart, links.size(), [&](std::size_t k) { return islandOfPair(links[k].a, links[k].b); });
}

} // namespace pba::rigid
